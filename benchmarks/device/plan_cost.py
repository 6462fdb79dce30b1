"""What a new transform length costs on the device: the zero-block DC-FFT convolution of an m x m
field (padded length 2m; :class:`viscontact.numerics.fftbackends.ZeroBlockTransforms`, four 1-D transforms)
after a kernel spectrum's forward transform, the first time a length is seen (CuPy makes and caches
its cuFFT plans) against later calls.

    python benchmarks/device/plan_cost.py            # padded lengths of a creeping contact's windows
    python benchmarks/device/plan_cost.py --lengths 864 1024

A creeping contact's support window grows by a few cells a step; with ``scipy.fft.next_fast_len``
lengths every step has a new length (864, 900, 960, 972, 1000 at 1024^2: ``bench_device.py``'s
creep), on the device ladder (:func:`viscontact.numerics.arrays.device_fast_length`) a new one only when the
contact grows by a third. Prints one row per length: the first call, the median of later calls [ms],
and whether the length is on the ladder.
"""
from __future__ import annotations

import argparse
import time

import numpy as np

from viscontact.numerics.arrays import cupy_backend, device_fast_length
from viscontact.numerics.fftbackends import ZeroBlockTransforms


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lengths", type=int, nargs="+",
                        default=[864, 900, 960, 972, 1000, 1024, 1152, 1536, 2048])
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    gpu = cupy_backend()
    import cupy

    def timed(call) -> float:
        cupy.cuda.Device().synchronize()
        start = time.perf_counter()
        call()
        cupy.cuda.Device().synchronize()
        return 1e3 * (time.perf_counter() - start)

    warm = ZeroBlockTransforms(8, fft=gpu.fft)  # CuPy's own kernels compiled before the first row
    field = gpu.to_device(np.ones((8, 8)))
    warm.convolve(warm.forward(field), field)
    print("| padded length 2m | on the device ladder | first spectrum + product [ms] | later [ms] |")
    print("|---|---|---|---|")
    for length in args.lengths:
        m = length // 2
        transforms = ZeroBlockTransforms(m, fft=gpu.fft)
        field = gpu.to_device(np.random.default_rng(0).standard_normal((m, m)))

        def once() -> None:  # a window's kernel spectrum, then one product with it
            transforms.convolve(transforms.forward(field), field)

        first = timed(once)
        later = float(np.median([timed(once) for _ in range(args.repeats)]))
        print(f"| {length} | {'yes' if device_fast_length(length) == length else 'no'} | {first:.1f} | {later:.2f} |")


if __name__ == "__main__":
    main()
