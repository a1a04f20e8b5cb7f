"""Green's function benchmarks (solvers/greens/kernels.py): `run() -> str` gives the markdown section.

    OMP_NUM_THREADS=1 .venv/bin/python -m benchmarks.greens

Wall-clock medians after warm-up (numba compiled), one process, dt = 36 us.  The
C20 modal data come from build/wheels/c20/modes.npz when it exists (else the
synthetic C20 modal set of pipeline/validation/references/greens.py); the rail kernel from the analytic beam
on a damped foundation of pipeline/validation/references/greens.py (the rail stage will supply the
waveguide-FE transfer receptance).
"""
from __future__ import annotations


import numpy as np

from benchmarks.timing import median_time

from solvers.constants import thesis_contact_point
from solvers.greens.kernels import (choose_grid, convolve_direct, convolve_fft, filter_history, green_from_receptance,
                           modal_filter, modal_kernel, moving_green, ring_convolver, ring_step)
from solvers.wheel.receptance import wheel_receptance
from pipeline.validation.references.greens import DT, V, beam_transfer, wheel_case


def _ring_loop(rc, F):
    import numba

    @numba.njit(cache=False)
    def loop(rc, F):
        s = 0.0
        for n in range(F.shape[0]):
            a, b = ring_step(rc, F[n, 0], F[n, 1])
            s += a + b
        return s

    return loop


def run() -> str:
    rows = []
    w = wheel_case(thesis_contact_point(-0.015)[0])  # the default case's y^W
    args = (w["f_hz"], w["modal_mass"], w["n"], w["phi"], w["zeta"])
    n_t = choose_grid(w["f_hz"], w["zeta"], DT)
    t_green = median_time(lambda: green_from_receptance(lambda f: wheel_receptance(f, *args), DT, n_t), 3, warm=1)
    rows.append(f"| C20 wheel Green's function by Kropp's method, {len(w['f_hz'])} modes, G22/G33/G23, "
                f"N_t = {n_t} from choose_grid ({n_t * DT:.0f} s, {n_t // 2 + 1} lags) | {t_green:.2f} s |")
    # recursive filters vs direct convolution
    rng = np.random.default_rng(0)
    fr = np.concatenate([w["f_hz"], [800.0, 3000.0]])
    mr = np.concatenate([w["modal_mass"], [30.0, 20.0]])
    z = np.concatenate([w["zeta"], [1.0, 2.5]])
    phi = np.vstack([w["phi"], [[0.3, 0.8], [-0.6, 0.2]]])
    nt = 200_000
    F = rng.standard_normal((nt, 2))
    filt = modal_filter(DT, fr, mr, z, phi)
    t_b = median_time(lambda: modal_filter(DT, fr, mr, z, phi), 5, warm=1)
    filter_history(filt.copy_reset(), F[:10])
    t_f = median_time(lambda: filter_history(filt.copy_reset(), F), 3, warm=1)
    rows.append(f"| wheel recursive modal filters, {len(fr)} modes: build | {1e6 * t_b:.0f} us |")
    rows.append(f"| wheel recursive modal filters, {len(fr)} modes, per step (njit loop over {nt} steps) | "
                f"{1e9 * t_f / nt:.0f} ns/step |")
    t_s = median_time(lambda: [filt.step(1.0, 2.0) for _ in range(10000)], 3, warm=1) / 10000
    rows.append(f"| same, one `ModalFilter.step` call from Python | {1e6 * t_s:.1f} us/step |")
    for K in (2000, 20000):
        g = modal_kernel(K, DT, fr, mr, z, phi)
        Fd = F[:20000]
        convolve_direct(g[:10], Fd[:10])
        t_d = median_time(lambda: convolve_direct(g, Fd), 2, warm=1)
        # the work of a full kernel: every step sums K - 1 lags once the history is longer than K
        per = t_d / sum(min(n, K - 1) for n in range(1, len(Fd))) * (K - 1)
        rows.append(f"| direct convolution, kernel of {K} lags ({K * DT * 1e3:.0f} ms), per step at full length | "
                    f"{1e6 * per:.1f} us/step |")
    n_full = n_t // 2
    rows.append(f"| direct convolution with the full C20 kernel ({n_full} lags), per step (extrapolated) | "
                f"{1e6 * per * n_full / (K - 1) / 1e3:.0f} ms/step |")
    # rail: moving Green's function, ring buffer, FFT
    tr = beam_transfer()
    n_tr, n_k = 8192, 2000
    moving_green(tr, V, DT, 16, n_tr)
    t_m = median_time(lambda: moving_green(tr, V, DT, n_k, n_tr), 2, warm=1)
    rows.append(f"| rail moving Green's function, beam on damped foundation, {n_k} lags, N_t = {n_tr} "
                f"({n_tr // 2 + 1} frequencies per lag) | {t_m:.2f} s |")
    zero = lambda x, f: np.zeros((len(x), len(f), 2, 2), complex)
    t_m0 = median_time(lambda: moving_green(zero, V, DT, n_k, n_tr), 2, warm=1)
    rows.append(f"| of which the construction itself (transfer receptance evaluation excluded) | {t_m0:.2f} s |")
    gr = moving_green(tr, V, DT, n_k, n_tr)
    rc = ring_convolver(gr)
    loop = _ring_loop(rc, F)
    loop(rc, F[:10])
    t_r = median_time(lambda: loop(rc, F), 2, warm=1)
    rows.append(f"| rail ring-buffer convolution, {n_k} lags, per step (njit loop over {nt} steps) | "
                f"{1e6 * t_r / nt:.2f} us/step |")
    t_fft = median_time(lambda: convolve_fft(gr, F), 3, warm=1)
    rows.append(f"| rail overlap-add FFT convolution of a whole history, {n_k} lags, {nt} steps ({nt * DT:.1f} s) | "
                f"{t_fft:.2f} s ({1e9 * t_fft / nt:.0f} ns/step) |")
    return f"""## Green's functions

`solvers/greens/kernels.py`, dt = 36 us, C20 modal data: {w['source']}; rail: Euler-Bernoulli beam on a damped foundation
(pipeline/validation/references/greens.py). Medians of repeated runs after warm-up (numba compiled), one process.

| operation | time |
|---|---:|
""" + "\n".join(rows) + """

The wheel's seconds-long kernel is never convolved directly in the time loop: the recursive modal filters are
exact (1e-13 relative to direct convolution, docs/validation/50_greens.md) and cost O(modes) per step. The rail's
moving kernel (a few thousand lags) is convolved per step by the partitioned FFT convolution (section "Rail fast
paths"); the ring buffer above is its direct reference.
"""


if __name__ == "__main__":
    print(run())
