#!/usr/bin/env bash
# Run THERE, on the lent GPU machine, in ONE call (about 9 minutes at most; docs/gpu.md):
#
#     run(carry=[".whl"], timeout_s=590, command="bash benchmarks/device/check.sh")
#
# 1. installs the carried wheels the image lacks (.whl/, from prepare.sh) into /tmp/site;
# 2. prints the GPU (nvidia-smi -L), the versions, and a CuPy smoke test (a transform on the device);
# 3. runs tests/unit/test_array_seam.py on the real CuPy backend (VISCONTACT_TEST_DEVICE=gpu: every
#    device test on cupy_backend(), each skipped with its reason where CuPy finds no CUDA device);
# 4. runs benchmarks/device/cli_check.py: viscontact run and steady of seed Table 1 on the CPU and on
#    the GPU (solver.device = "gpu"), timed, their results compared;
# 5. runs benchmarks/device/plan_cost.py: what a new transform length (a new cuFFT plan) costs;
# 6. runs benchmarks/bench_device.py at 1024^2 and at 2048^2 (BENCH_STEPS steps, CPU rows and GPU
#    rows: the device ladder, scipy's lengths at 1024^2, and the CG deciding on the host every iteration
#    against its resident scalars, --host-cg); without a CUDA device only at 128^2 (the CPU
#    rows and "no CUDA device"), to check the path;
# 7. runs benchmarks/bench_device.py --cases rough --gpu-only at 4096^2: the shipped rough periodic case in
#    gross sliding with friction on the GPU alone (time a step, CG iterations, CuPy's pool); its set-up
#    (the surface and the periodic kernels, on the host) takes a minute or two. Without a device: at 64^2.
#
# Every stage runs under `timeout` within CHECK_BUDGET seconds in all; logs go to $OUT/ (or
# out/device/ where $OUT is unset): env.txt, install.log, seam.log, seam.xml, bench_<n>.md,
# cli.md, plans.md, rough_4096.md, summary.txt. CHECK_STAGES (default "seam cli plans bench rough") reruns some (install and
# environment, a few seconds, always run). Exit status: the first failing stage's (a stage timed out: 124), else 0 (no CUDA
# device: the tests skipped, the status 0).
set -uo pipefail
cd "$(dirname "$0")/../.."
OUT=${OUT:-$PWD/out/device}
mkdir -p "$OUT"
BUDGET=${CHECK_BUDGET:-540}
BENCH_STEPS=${BENCH_STEPS:-6}
STAGES=${CHECK_STAGES:-seam cli plans bench rough}  # a rerun of some: CHECK_STAGES="seam", "bench", ... (install and environment always run)
if [ -z "${PYTHON:-}" ]; then
    if [ -x /opt/torch/.venv/bin/python3 ]; then PYTHON=/opt/torch/.venv/bin/python3; else PYTHON=python3; fi
fi
SITE=${CHECK_SITE:-/tmp/site}
export PYTHONPATH="$SITE:$PWD/src${PYTHONPATH:+:$PYTHONPATH}"
export CUPY_CACHE_DIR=${CUPY_CACHE_DIR:-/tmp/cupy_kernel_cache}
export PYTHONDONTWRITEBYTECODE=1
STATUS=0
: > "$OUT/summary.txt"

# stage NAME CAP LOG COMMAND...: runs COMMAND under timeout (CAP seconds or what is left of the
# budget), its output to LOG and to the terminal; records the status and the time in summary.txt
stage() {
    local name=$1 cap=$2 log=$3
    shift 3
    local left=$((BUDGET - SECONDS))
    local limit=$((cap < left ? cap : left))
    if [ "$limit" -le 5 ]; then
        echo "$name: not run (the budget of ${BUDGET} s is spent)" | tee -a "$OUT/summary.txt"
        [ "$STATUS" -eq 0 ] && STATUS=124
        return
    fi
    local start=$SECONDS
    echo "== $name (limit ${limit} s)"
    timeout --kill-after=10 "$limit" "$@" 2>&1 | tee "$log"
    local rc=${PIPESTATUS[0]}
    echo "$name: status $rc, $((SECONDS - start)) s (limit ${limit} s)" | tee -a "$OUT/summary.txt"
    if [ "$rc" -ne 0 ] && [ "$STATUS" -eq 0 ]; then STATUS=$rc; fi
}

install_wheels() {
    local wheels=""
    if [ ! -d .whl ]; then  # the environment stage's imports say what is missing, if anything
        echo "no .whl/ (where the image lacks packages: run benchmarks/device/prepare.sh first, carry .whl)"
    else
        wheels=$("$PYTHON" benchmarks/device/wheels.py missing .whl) || return 1
    fi
    if [ -z "$wheels" ]; then
        echo "every carried wheel's package is installed already"
    else
        echo "installing:" $wheels
        # shellcheck disable=SC2086
        "$PYTHON" -m pip install -q --disable-pip-version-check --no-index --no-deps --no-compile --no-cache-dir \
            --target "$SITE" $wheels || return 1
    fi
    # viscontact runs from src/, not installed: its version (result files record it) where metadata
    # looks for it
    "$PYTHON" benchmarks/device/wheels.py source-metadata "$SITE"
}

environment() {
    echo "python: $PYTHON ($("$PYTHON" -V 2>&1)); PYTHONPATH=$PYTHONPATH"
    if command -v nvidia-smi > /dev/null; then nvidia-smi -L; else echo "nvidia-smi: not found"; fi
    "$PYTHON" - <<'PY'
import importlib, importlib.metadata as md
for dist in ("numpy", "scipy", "xarray", "h5py", "h5netcdf", "pydantic", "SurfaceTopography", "cupy-cuda13x",
             "pytest", "pytest-xdist", "hypothesis"):
    try:
        print(f"{dist} {md.version(dist)}")
    except md.PackageNotFoundError:
        print(f"{dist}: not installed")
import viscontact.io.case, viscontact.io.streaming  # pydantic, h5netcdf on import
from SurfaceTopography.Generation import fourier_synthesis  # the rough case's surface
print("viscontact", viscontact.__file__)
from viscontact.numerics.arrays import cupy_backend
try:
    gpu = cupy_backend()
except ImportError as exc:
    print(f"no CUDA device: {exc}")
    raise SystemExit(0)
import cupy, numpy as np
props = cupy.cuda.runtime.getDeviceProperties(cupy.cuda.Device().id)
print("device:", props["name"].decode(), f"{props['totalGlobalMem'] / 2**30:.0f} GiB,",
      "CUDA runtime", cupy.cuda.runtime.runtimeGetVersion(), "driver", cupy.cuda.runtime.driverGetVersion())
field = np.random.default_rng(0).standard_normal((64, 64))
back = gpu.to_host(gpu.fft.irfft2(gpu.fft.rfft2(gpu.to_device(field)), s=field.shape))
print("smoke: irfft2(rfft2(x)) on the device, max error", float(np.max(np.abs(back - field))))
PY
}

has_device() {
    "$PYTHON" -c "from viscontact.numerics.arrays import cupy_backend; cupy_backend()" > /dev/null 2>&1
}

export PYTHON SITE
export -f install_wheels environment  # for the bash that timeout starts
wanted() { [[ " $STAGES " == *" $1 "* ]]; }
stage install 90 "$OUT/install.log" bash -c install_wheels
stage environment 60 "$OUT/env.txt" bash -c environment
wanted seam && stage seam 240 "$OUT/seam.log" env VISCONTACT_TEST_DEVICE=gpu "$PYTHON" -m pytest -q -rs -p no:cacheprovider \
    -n "${SEAM_WORKERS:-4}" --durations=10 --junitxml="$OUT/seam.xml" tests/unit/test_array_seam.py \
    tests/unit/test_fftbackends.py::test_solver_device_and_mixed_precision_are_case_keys
if ! has_device; then
    echo "no CUDA device: the benchmark runs at 128^2 only, to check its path" | tee -a "$OUT/summary.txt"
    wanted bench && stage bench_128 120 "$OUT/bench_128.md" "$PYTHON" -u benchmarks/bench_device.py --n 128 --steps 3
    wanted rough && stage rough_64 60 "$OUT/rough_64.md" "$PYTHON" -u benchmarks/bench_device.py --n 64 --steps 3 \
        --cases rough --gpu-only
else
    wanted cli && stage cli 90 "$OUT/cli.md" "$PYTHON" -u benchmarks/device/cli_check.py
    wanted plans && stage plans 40 "$OUT/plans.md" "$PYTHON" -u benchmarks/device/plan_cost.py
    if wanted bench; then
        stage bench_1024 120 "$OUT/bench_1024.md" "$PYTHON" -u benchmarks/bench_device.py --n 1024 --steps "$BENCH_STEPS" --scipy-lengths --host-cg
        stage bench_2048 200 "$OUT/bench_2048.md" "$PYTHON" -u benchmarks/bench_device.py --n 2048 --steps "$BENCH_STEPS" --host-cg
    fi
    wanted rough && stage rough_4096 180 "$OUT/rough_4096.md" "$PYTHON" -u benchmarks/bench_device.py --n 4096 \
        --steps "$BENCH_STEPS" --cases rough --gpu-only
fi
echo "== summary ($SECONDS s in all; logs in $OUT)"
cat "$OUT/summary.txt"
exit "$STATUS"
