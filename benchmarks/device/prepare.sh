#!/usr/bin/env bash
# Run HERE, on a machine with network, before a GPU session: downloads into .whl/ the wheels the
# GPU image lacks (benchmarks/device/wheels.py: pinned, CPython 3.12, manylinux x86-64), keeps one
# version of each, checks that every requirement is on the image or carried, and prints the sizes.
# .whl/ is ignored (.gitignore); the GPU session carries it: run(carry=[".whl"], ...). See docs/gpu.md.
set -euo pipefail
cd "$(git rev-parse --show-toplevel)"
PY=${PYTHON:-python3}
mkdir -p .whl
if ! git check-ignore -q .whl/x.whl; then  # a checkout without this branch's .gitignore
    echo "/.whl/" >> "$(git rev-parse --git-common-dir)/info/exclude"
fi
# shellcheck disable=SC2046
"$PY" -m pip download -q --disable-pip-version-check --no-deps --only-binary=:all: --python-version 3.12 \
    --implementation cp --platform manylinux_2_28_x86_64 --platform manylinux_2_17_x86_64 \
    --platform manylinux2014_x86_64 -d .whl $("$PY" benchmarks/device/wheels.py pins)
"$PY" benchmarks/device/wheels.py prune .whl
"$PY" benchmarks/device/wheels.py verify .whl
du -sh .whl
