"""Green's functions (impulse responses) of the wheel and the rail, and the
convolutions of the time loop (SPEC 3.3-3.5; thesis [4.3]-[4.15]).

Units and conventions
---------------------
A discrete kernel g[k] (m/N) maps a force sample to a displacement:
xi(t_d) = sum_tau F(tau) g(t_d - tau), i.e. g[k] = dt * g_c(k dt) with g_c the
continuous impulse response (m/(N s)).  Matrix kernels have shape
(n_lags, 2, 2), index 0 = direction 2 (lateral, toward the field side),
1 = direction 3 (vertical, toward the ground), g[k, i, j] = response in i to a
force in j (so g[:, 0, 1] is g23), the same layout as the receptances of
``solvers.wheel.receptance`` and ``solvers.rail.response``.

Every convolution here excludes the instantaneous term g[0] (SPEC 3.5, [4.13],
[4.15]): the displacement at step n depends on forces at steps <= n - 1,

    xi[n] = sum_{k=1}^{n} g[k] @ F[n - k].

The per-step objects (``ModalFilter``, ``RingConvolver``) therefore take the
force of the current step and return the displacement of the NEXT step:
``xi_next = obj.step(F2, F3)``; before the first call the displacement is 0.
The kernels are the plain Green's functions: the wheel stage applies the minus
sign of [4.13] (the wheel receives -F), the rail stage uses them as they are;
both convolve force deviations from the static preload (SPEC 3.5).

Kropp's method [4.3]-[4.5]
--------------------------
S(f_k) = 2 Re G(f_k) on f_k = k / (N_t dt), k = 0..N_t/2, is the spectrum of
the EVEN extension g_c(|t|) of the causal response (2 Re G = G + G*).  Its
continuous inverse transform sampled at n dt, approximated by the sum over the
grid (df = 1/(N_t dt)), is

    s(n dt) = df sum_k S_k exp(2 pi i k n / N_t) = N_t df ifft(S)[n] = ifft(S)[n] / dt,

so the thesis' g(n dt) = dt s(n dt) [4.5] is simply ``ifft(S)[n]`` (numpy's
``ifft`` divides by N_t) for n = 1..N_t/2 and half of it at n = 0.  The SDOF
test (tests/greens/test_green.py) confirms it: g[k] = ifft(S)[k] matches
dt * exp(-zeta w t) sin(w_d t) / (m w_d) to < 1e-4 of the peak beyond the first
20 samples; ifft(S)/dt or dt * ifft(S) would be off by factors 1/dt^2, dt^2.
Because g is the causal half of the even sequence ifft(S), Re(DFT g) = S/2 =
Re G exactly on the grid; the imaginary part is the discrete Hilbert transform
of Re G, which lacks the spectrum above the Nyquist frequency (the mass-line
tails): that is the only approximation besides the decay by N_t/2 dt.  In time
it is an error of the first samples, 2 f0 dt / pi of the peak at k = 0 and
~ 8 f0 dt / (pi^3 k^2) after; in frequency an absolute Im error growing ~ f
(a few 1e-12 m/N at 6 kHz for the C20, of the sign of negative damping: the
kernel is slightly non-passive off-resonance above ~2.6 kHz).  The sampled
modal kernel of the filters below has a passive Im instead and a constant real
offset -C dt^2/12, C = sum phi phi^T / m_r (docs/validation/50_greens.md).
A second, smaller Im error is the truncation at N_t/2: 2 sum_{n > N_t/2}
g_c(n dt) sin(2 pi f_k n dt), alternating in sign from one grid point to the
next (it is what the folded tail leaves); it falls with the decay reached at
N_t/2 dt (``choose_grid(.., decay_db)``).

Band-limited correction (``band_limit``, SPEC 3.3)
---------------------------------------------------
Kropp's Im error is harmless against the level of the receptance but not
pointwise at deep antiresonances (|G22| ~ 7e-13 m/N between the sparse C20
peaks: tens to hundreds of % there).  Only the band up to ``band_limit`` (the
6.5 kHz of the models) has to be right; the spectrum between band_limit and
the Nyquist frequency 1/(2 dt) is free.  The error lives in the first
samples (above), so ``green_from_receptance(.., band_limit=f_b)`` refits the
first ``taps`` samples g[0..taps-1] (g[0] included): a correction h with

    sum_{k < taps} h[k] exp(-2 pi i f k dt) = G(f) - DFT(g)(f),  0 < f <= f_b,

by weighted least squares relative to |G| (weights 1/min|G| over each fit
segment, so antiresonances count as much as peaks), on ~2000 frequencies
(each the mean of two neighbouring grid points, which averages the
alternating truncation error out), Tikhonov-regularised to the smallest
correction that reaches ``fit_tol`` (discrepancy principle).  The error
against f is smooth (a trigonometric polynomial of degree ~ taps fits it to
1e-4 relative over 47 % of the circle), the band above f_b absorbs the rest.
Nothing beyond lag taps - 1 changes (the SDOF and modal-kernel comparisons
beyond 20 samples are untouched); Re DFT(g) is then exact only to the fit
tolerance instead of to rounding.  The corrected kernel is real, causal and
decays as before, and passive in the band; the band above f_b pays for it:
there its spectrum departs from G by a few |G| and is non-passive in places
(C20: -Im DFT(g) down to -7e-11 m/N, plain Kropp -6e-12), so a corrected
kernel convolved in a time loop could feed spurious growth above f_b.  The
greens stage corrects the wheel kernel, which the time loop does not use
(it uses the modal filters below); the rail kernel it convolves is plain
Kropp.  The correction assumes a causal receptance: for one with hysteretic
(constant loss factor) damping, Im G(0+) != 0 and no causal kernel reproduces
it (the BV50 rail, see pipeline/stages/greens.py); the fit would chase the
non-causal part and is not used there.

Wheel: exact recursive modal filters
------------------------------------
The wheel receptance is a modal sum [4.10], so its sampled impulse response is
a sum of damped sinusoids,

    g_r[k] = dt Phi_ri Phi_rj / m_r * h_r(k dt),
    h_r(t) = exp(-sigma t) sinh(mu t) / mu,  sigma = zeta w,  mu = w sqrt(zeta^2 - 1),

(mu = i w_d for zeta < 1: exp(-zeta w t) sin(w_d t) / w_d; t exp(-w t) at
zeta = 1; two real exponentials for zeta > 1).  The discrete convolution of a
force history with it is reproduced EXACTLY (to rounding) by one recursion per
mode on the modal force P_r = Phi_r2 F2 + Phi_r3 F3:

* zeta < 1: complex one-pole form, z = exp((-sigma + i w_d) dt),
  q[n+1] = z (q[n] + P[n]),  xi_i[n] += Phi_ri dt / (m_r w_d) Im q[n]
  (q[n] = sum_{k>=1} z^k P[n-k]; better conditioned than the real
  two-term recursion for the low-frequency rigid modes, whose poles are
  close to z = 1);
* zeta >= 1: real poles p1,2 = exp((-sigma +- mu) dt), divided-difference
  states a[n] = sum p2^k P[n-k], v[n] = sum d_k P[n-k] with
  d_k = (p1^k - p2^k)/(p1 - p2) (= k p^(k-1) at zeta = 1, no cancellation):
  v[n+1] = P[n] + p1 v[n] + a[n],  a[n+1] = p2 (a[n] + P[n]),
  xi_i[n] += Phi_ri / m_r * dt * (p1 - p2)/(s1 - s2) * v[n]
  with (p1 - p2)/(s1 - s2) = dt exp(-sigma dt) sinh(mu dt)/(mu dt).

The kernel these filters reproduce is ``modal_kernel`` (the sampled modal
impulse response), not Kropp's g (plain or band-limited): the two differ only
in the first samples (Kropp's band limit, or the correction) and by time
aliasing (documented in 50_greens.md).

Rail
----
The rail kernel (a few thousand lags, fast pad-damped decay) is convolved
directly (``convolve_direct``; per step with ``RingConvolver``) or by
overlap-add FFT over a whole history (``convolve_fft``).  The moving Green's
function (SPEC 3.4) g_mov[k] = g^R(x_k = v k dt, k dt) is Kropp's construction
evaluated at the single lag k from the transfer receptance at x_k
(``moving_green``).
"""
# The public names of the Green's functions; the code lives one idea a module: kropp (Kropp's
# method, grid, decay check), band_fit (the band-limited correction), modal_filter (the wheel's
# modal kernel and recursive filters), convolution (direct, FFT, ring), moving_green (the rail's
# moving kernel by Kropp per lag; the fast form is solvers.rail.moving_kernel).
from solvers.greens.band_fit import BandFit  # noqa: F401
from solvers.greens.convolution import RingConvolver, RingState, convolve_direct, convolve_fft, ring_convolver, ring_step
from solvers.greens.kropp import DecayCheck, GreenDecayError, choose_grid, decayed, frequency_grid, green_from_receptance, points_in_band
from solvers.wheel.modal_filter import FilterState, ModalFilter, filter_history, filter_step, modal_filter, modal_impulse, modal_kernel
from solvers.rail.moving_green import moving_green  # noqa: F401
