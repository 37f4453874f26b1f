"""The game's sounds, made from code with numpy (no recorded samples): loops of filtered noise for wind,
rain and the watering can's pour, pulsed tones for crickets, and one-shots for birds, chimes and clicks.

Loops are made periodic (noise filtered in the frequency domain over the loop's own length, modulations
with whole cycles per loop), so they repeat without a click at the seam. Every sound is mono float
-1..1 at RATE samples a second; :func:`stereo16` turns one into what pygame's mixer plays.
"""

from __future__ import annotations

import numpy as np

RATE = 22050  # samples a second (enough for these sounds, half the work of 44.1 kHz)


def _noise_band(seconds: float, low: float, high: float, rng: np.random.Generator) -> np.ndarray:
    """Periodic noise of ``seconds`` with only the frequencies from ``low`` to ``high`` Hz, peak 1."""
    n = int(seconds * RATE)
    spectrum = np.fft.rfft(rng.standard_normal(n))
    f = np.fft.rfftfreq(n, 1.0 / RATE)
    spectrum *= np.exp(-0.5 * ((np.log(np.maximum(f, 1.0)) - np.log(np.sqrt(low * high))) / np.log(high / low)) ** 2
                       * 8.0)
    out = np.fft.irfft(spectrum, n)
    return out / max(float(np.abs(out).max()), 1e-9)


def _cycles(seconds: float, per_loop: int, phase: float = 0.0) -> np.ndarray:
    """A sine with a whole number of cycles per loop (a modulation that loops without a seam)."""
    t = np.arange(int(seconds * RATE)) / (seconds * RATE)
    return np.sin(2 * np.pi * per_loop * t + phase)


def wind(seconds: float = 6.0, seed: int = 1) -> np.ndarray:
    """Low rushing noise that swells and eases (a loop)."""
    rng = np.random.default_rng(seed)
    body = _noise_band(seconds, 120.0, 700.0, rng)
    swell = 0.65 + 0.25 * _cycles(seconds, 1) + 0.1 * _cycles(seconds, 3, 1.3)
    return 0.8 * body * swell


def rain(seconds: float = 4.0, seed: int = 2) -> np.ndarray:
    """A hiss of fine drops with louder ones pattering in it (a loop)."""
    rng = np.random.default_rng(seed)
    hiss = 0.45 * _noise_band(seconds, 2000.0, 9000.0, rng)
    n = len(hiss)
    drops = np.zeros(n)
    tail = np.exp(-np.arange(200) / 25.0) * rng.standard_normal(200)
    for at in rng.integers(0, n, size=int(seconds * 60)):
        np.add.at(drops, (at + np.arange(len(tail))) % n, tail * rng.uniform(0.2, 0.8))  # (round the seam)
    return np.clip(hiss + drops, -1.0, 1.0) * 0.8


def pour(seconds: float = 3.0, seed: int = 3) -> np.ndarray:
    """Water poured from a can: a splashing band of noise with bubbles rising in pitch (a loop)."""
    rng = np.random.default_rng(seed)
    splash = 0.5 * _noise_band(seconds, 400.0, 3000.0, rng) * (0.8 + 0.2 * _cycles(seconds, 7))
    n = len(splash)
    bubbles = np.zeros(n)
    for at in rng.integers(0, n - 2000, size=int(seconds * 14)):
        length = int(rng.uniform(0.02, 0.06) * RATE)
        t = np.arange(length) / RATE
        f = rng.uniform(350.0, 900.0) * (1.0 + 6.0 * t)
        bubbles[at:at + length] += 0.35 * np.sin(2 * np.pi * np.cumsum(f) / RATE) * np.exp(-t * 60.0)
    return np.clip(splash + bubbles, -1.0, 1.0) * 0.8


def crickets(seconds: float = 2.0, seed: int = 4) -> np.ndarray:
    """Crickets at night: trills of a high tone, three pulses at a time (a loop)."""
    rng = np.random.default_rng(seed)
    n = int(seconds * RATE)
    t = np.arange(n) / RATE
    out = np.zeros(n)
    for pitch, start in ((4400.0, 0.0), (4700.0, 0.27 + 0.1 * rng.random())):
        chirp = (t - start) % 0.5  # a trill every half second
        pulses = (chirp < 0.12) * (np.sin(2 * np.pi * chirp / 0.04) > 0.0)
        out += 0.35 * np.sin(2 * np.pi * pitch * t) * pulses
    return out


def bird(seed: int = 5) -> np.ndarray:
    """One bird's call: three to five quick whistles sweeping up and down (a one-shot)."""
    rng = np.random.default_rng(seed)
    notes = []
    for _ in range(int(rng.integers(3, 6))):
        length = int(rng.uniform(0.06, 0.12) * RATE)
        t = np.arange(length) / RATE
        f0, f1 = rng.uniform(2200.0, 3200.0), rng.uniform(3000.0, 4500.0)
        f = f0 + (f1 - f0) * np.sin(np.pi * t / t[-1])
        notes.append(0.5 * np.sin(2 * np.pi * np.cumsum(f) / RATE) * np.sin(np.pi * t / t[-1]) ** 2)
        notes.append(np.zeros(int(rng.uniform(0.03, 0.08) * RATE)))
    return np.concatenate(notes)


def chime(seconds: float = 2.5) -> np.ndarray:
    """A soft bell: a few inharmonic partials dying away (a milestone)."""
    t = np.arange(int(seconds * RATE)) / RATE
    partials = ((880.0, 1.0, 1.6), (1760.0 * 1.003, 0.45, 2.4), (2640.0 * 0.996, 0.25, 3.5), (3960.0, 0.1, 5.0))
    out = sum(a * np.sin(2 * np.pi * f * t) * np.exp(-t * d) for f, a, d in partials)
    return 0.45 * out * np.minimum(t / 0.005, 1.0)


def click() -> np.ndarray:
    """A short wooden tick (a button pressed)."""
    t = np.arange(int(0.04 * RATE)) / RATE
    return 0.6 * np.sin(2 * np.pi * 1500.0 * t) * np.exp(-t * 160.0)


def stereo16(sound: np.ndarray) -> np.ndarray:
    """A mono float sound as the mixer's (n, 2) int16 samples."""
    samples = (np.clip(sound, -1.0, 1.0) * 32000.0).astype(np.int16)
    return np.ascontiguousarray(np.column_stack([samples, samples]))
