"""The predicted squeal as a sound: onset from the simulation's growth phase,
then the limit cycle, as calibrated 16-bit PCM at 44.1 kHz.

Pure functions on arrays (the WAV is returned as bytes; the pipeline's
``listen`` stage writes it atomically).

Signal model
------------
* Limit cycle: the sum of the squeal's tones (the radiate stage's tones, at
  their own fitted frequencies, each with its complex RMS pressure at the
  receiver from ``listener.transfer``; the source phase of a tone is its
  fitted F2 phase, which shapes the waveform but not the levels) plus the
  residual as Gaussian noise with the residual's pressure spectrum (random
  phases, fixed seed), synthesized directly at 44.1 kHz (no resampling of the
  tones: their frequencies stay exact).
* Onset: in the growth phase every state of the linearised wheel/rail system
  grows with the same exponential rate (the unstable eigenvalue), so the
  wheel velocity, hence the pressure, follows the envelope of the contact
  force F2.  The envelope is the running RMS of F2 (running mean removed,
  ``ENVELOPE_WINDOW_S``) of the simulation's stored history, divided by its
  value over the last ``REFERENCE_S`` of that history; the limit-cycle signal
  is multiplied by it (no frequency glide during the growth).  The sound
  starts ``ONSET_S`` before the envelope first reaches -1 dB of the limit
  cycle (or at the start of the history) and holds the limit cycle for
  ``HOLD_S``; ``FADE_S`` raised-cosine fades at both ends avoid clicks.
* Calibration: the peak of the signal is put ``HEADROOM_DB`` below full scale;
  a sample value v (int16) is v * ``pa_per_count`` Pa, so a full-scale sine
  (peak 32767 counts) has the level 20 log10(32767 pa_per_count / (sqrt 2 p0)).
  TPDF dither of +-1 LSB before rounding (fixed seed).  A silent file (all
  zeros) gets a nominal calibration of 1 Pa at full scale.
"""
from __future__ import annotations

import io
import struct
from dataclasses import dataclass

import numpy as np

FS = 44100  # Hz, sample rate of the WAV
FULL_SCALE = 32767  # int16 counts at full scale
HEADROOM_DB = 1.0  # peak of the signal below full scale (dB)
ENVELOPE_WINDOW_S = 0.02  # s, running RMS window of the growth envelope
REFERENCE_S = 0.5  # s, the limit-cycle reference at the end of the history (SPEC 6's final stretch)
ONSET_S = 3.0  # s of growth before the limit cycle, at most
HOLD_S = 2.0  # s of limit cycle after the onset
FADE_S = 0.01  # s, raised-cosine fade in and out
SILENT_FULL_SCALE_PA = 1.0  # Pa at full scale for a silent file (nominal)


def aliased(f: float, fs: float) -> float:
    """The frequency (Hz) a tone at f shows at the sample rate fs (folded into 0..fs/2)."""
    r = float(f) % fs
    return min(r, fs - r)


def growth_envelope(t, x, window: float = ENVELOPE_WINDOW_S, reference: float = REFERENCE_S,
                    f_tone: float | None = None):
    """Running RMS of ``x(t)`` (running mean removed, both over ``window`` s),
    divided by the RMS of x (mean removed) over the last ``reference`` s.
    Returns (t, envelope); the envelope is 1 in the limit cycle.  The stored
    history is decimated, so the tone ``f_tone`` (Hz) may alias: the window is
    widened to 3 periods of its aliased frequency.  Raises ValueError when the
    history has no oscillation at its end, or the tone aliases to below
    3 / ``reference`` Hz (no envelope can be told from the mean force)."""
    from scipy.ndimage import uniform_filter1d  # lazy: brings in scipy

    t, x = np.asarray(t, float), np.asarray(x, float)
    if t.size < 8 or t.shape != x.shape:
        raise ValueError(f"history: need matching t, x with >= 8 samples, got {t.shape}, {x.shape}")
    dt = float(np.median(np.diff(t)))
    if f_tone is not None and np.isfinite(f_tone):
        fa = aliased(f_tone, 1 / dt)
        if not fa > 3 / reference:
            raise ValueError(f"history: the tone at {f_tone:.1f} Hz aliases to {fa:.2f} Hz at the history's sample "
                             f"rate {1 / dt:.1f} Hz: its envelope cannot be told from the mean force")
        window = max(window, 3 / fa)
    n = max(3, int(round(window / dt)))
    mean = uniform_filter1d(x, n, mode="nearest")
    env = np.sqrt(np.maximum(uniform_filter1d((x - mean) ** 2, n, mode="nearest"), 0.0))
    tail = x[t >= t[-1] - reference]
    ref = float(np.sqrt(np.mean((tail - tail.mean()) ** 2))) if tail.size > 1 else 0.0
    if not ref > 0:
        raise ValueError("history: no oscillation over its last stretch (constant force)")
    return t, env / ref


@dataclass(frozen=True)
class Onset:
    """The envelope of the sound: ``t`` (s, from 0), ``gain`` (1 = limit cycle);
    ``t_limit_cycle`` (s) where the limit cycle starts in the sound;
    ``t_history`` (s) the simulation time the sound starts at; ``duration`` (s)."""
    t: np.ndarray
    gain: np.ndarray
    t_limit_cycle: float
    t_history: float
    duration: float


def onset_from_history(t, env, onset: float = ONSET_S, hold: float = HOLD_S) -> Onset:
    """The sound's envelope: the last ``onset`` s of growth before ``env`` first
    reaches -1 dB of the limit cycle, a linear ramp to 1 over one envelope window, then
    ``hold`` s at 1."""
    t, env = np.asarray(t, float), np.asarray(env, float)
    above = np.flatnonzero(env >= 10 ** (-1 / 20))
    i_lc = int(above[0]) if above.size else t.size - 1
    t_lc = float(t[i_lc])
    t0 = max(float(t[0]), t_lc - onset)
    sel = (t >= t0) & (t <= t_lc)
    ramp = ENVELOPE_WINDOW_S  # from -1 dB to the limit cycle over one envelope window
    tt = np.r_[t[sel] - t0, t_lc - t0 + ramp, t_lc - t0 + ramp + hold]
    gg = np.r_[env[sel], 1.0, 1.0]
    return Onset(t=tt, gain=gg, t_limit_cycle=t_lc - t0 + ramp, t_history=t0, duration=t_lc - t0 + ramp + hold)


def tones(f, p_rms, n: int, fs: float = FS) -> np.ndarray:
    """sum_j sqrt(2) |p_j| cos(2 pi f_j t + arg p_j) over n samples at fs
    (``p_rms`` complex RMS amplitudes, Pa)."""
    t = np.arange(n) / fs
    out = np.zeros(n)
    for fj, pj in zip(np.atleast_1d(f), np.atleast_1d(p_rms)):
        out += np.sqrt(2) * abs(pj) * np.cos(2 * np.pi * fj * t + np.angle(pj))
    return out


def shaped_noise(f, p2, n: int, fs: float = FS, seed: int = 0) -> np.ndarray:
    """Gaussian-like noise of n samples at fs with the mean-square spectrum ``p2``
    (Pa^2 per bin) given on the uniform bins ``f`` (Hz): the density p2/df is
    interpolated onto the signal's own DFT bins, random phases.  Its mean square
    equals sum(p2) within the interpolation error."""
    f, p2 = np.asarray(f, float), np.asarray(p2, float)
    if f.size < 2 or not np.any(p2 > 0):
        return np.zeros(n)
    df_in = float(np.median(np.diff(f)))
    fk = np.fft.rfftfreq(n, 1 / fs)
    p2k = np.interp(fk, f, p2 / df_in, left=0.0, right=0.0) * (fs / n)
    p2k[0] = 0.0
    if n % 2 == 0:
        p2k[-1] = 0.0
    s = p2.sum() / p2k.sum() if p2k.sum() > 0 else 0.0  # keep the total mean square exactly
    phase = np.random.default_rng(seed).uniform(0, 2 * np.pi, fk.size)
    X = n * np.sqrt(s * p2k / 2) * np.exp(1j * phase)  # irfft: mean square = sum p2k
    return np.fft.irfft(X, n)


def apply_onset(p, onset: Onset, fs: float = FS, fade: float = FADE_S) -> np.ndarray:
    """p(t) times the onset gain (interpolated to the sample times) and the fades."""
    n = p.size
    t = np.arange(n) / fs
    g = np.interp(t, onset.t, onset.gain)
    m = min(int(round(fade * fs)), n // 2)
    if m > 0:
        ramp = 0.5 - 0.5 * np.cos(np.pi * np.arange(m) / m)
        g[:m] *= ramp
        g[n - m:] *= ramp[::-1]
    return p * g


def to_pcm16(p, headroom_db: float = HEADROOM_DB, seed: int = 1):
    """(int16 samples, Pa per count) of the pressure p (Pa): the peak at
    ``headroom_db`` below full scale, TPDF dither; all-zero input gives zeros at
    the nominal calibration SILENT_FULL_SCALE_PA."""
    p = np.asarray(p, float)
    peak = float(np.max(np.abs(p))) if p.size else 0.0
    if not peak > 0:
        return np.zeros(p.size, np.int16), SILENT_FULL_SCALE_PA / FULL_SCALE
    pa_per_count = peak * 10 ** (headroom_db / 20) / FULL_SCALE
    rng = np.random.default_rng(seed)
    dither = rng.uniform(-0.5, 0.5, p.size) + rng.uniform(-0.5, 0.5, p.size)
    v = np.clip(np.round(p / pa_per_count + dither), -FULL_SCALE, FULL_SCALE)
    return v.astype(np.int16), pa_per_count


def full_scale_sine_level(pa_per_count: float, p_ref: float = 20e-6) -> float:
    """Level (dB re p_ref) of a full-scale sine (peak FULL_SCALE counts)."""
    return float(20 * np.log10(FULL_SCALE * pa_per_count / np.sqrt(2) / p_ref))


def wav_bytes(samples, fs: int = FS, comment: str = "") -> bytes:
    """A mono 16-bit PCM WAV (scipy.io.wavfile) with the ``comment`` in a LIST/INFO
    ICMT chunk (ASCII; readers that do not know LIST skip it)."""
    from scipy.io import wavfile  # lazy: brings in scipy

    buf = io.BytesIO()
    wavfile.write(buf, int(fs), np.asarray(samples, np.int16))
    raw = bytearray(buf.getvalue())
    if comment:
        text = comment.encode("ascii", "replace") + b"\0"
        sub = b"ICMT" + struct.pack("<I", len(text)) + text + (b"\0" if len(text) % 2 else b"")
        raw += b"LIST" + struct.pack("<I", 4 + len(sub)) + b"INFO" + sub
        raw[4:8] = struct.pack("<I", len(raw) - 8)  # RIFF size
    return bytes(raw)


def wav_comment(data: bytes) -> str:
    """The ICMT comment of a WAV written by ``wav_bytes`` ('' when there is none)."""
    i = data.find(b"LIST")
    while i >= 0:
        if data[i + 8:i + 12] == b"INFO" and data[i + 12:i + 16] == b"ICMT":
            size = struct.unpack("<I", data[i + 16:i + 20])[0]
            return data[i + 20:i + 20 + size].rstrip(b"\0").decode("ascii")
        i = data.find(b"LIST", i + 4)
    return ""
