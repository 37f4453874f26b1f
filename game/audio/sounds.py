"""The game's sound service: what should be heard in a state of the garden (:class:`Soundscape`), and
:class:`Audio`, which plays it through pygame's mixer.

The game hands the service the soundscape each frame (:meth:`Audio.hear`); the service keeps one channel
per loop (wind, rain, pour, night) at a level set by the state (wind by its strength, the pour while the
watering can is held, crickets by how dark it is), calls a bird now and then by day, chimes once when the
journal gains a milestone and ticks when a button is pressed. Without a sound device (or with SDL's dummy
driver, as in CI) it works the same and is silent; if the mixer cannot start at all, it only keeps the
levels.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import numpy as np
import pygame

from arbor.game.audio import synth

LOOPS = ("wind", "rain", "pour", "night")  # one channel each, in this order
BIRDS = 3  # calls to choose from
BIRD_RATE = 0.18  # calls a second in full daylight (on average)
FADE_MS = 120  # a loop that stops fades out this long (no click)
WIND_FULL = 2.0  # wind strength (the rule's unit) at which the wind sounds its loudest
WIND_QUIET = 0.02  # below this strength the air is still: no wind sound


@dataclass(frozen=True)
class Soundscape:
    """What the garden sounds like now: how hard the wind blows (the rule's strength), whether it rains
    and the watering can pours, how light it is (0 night .. 1 day), how many milestones the journal
    holds (one more chimes) and how many buttons were pressed (one more clicks)."""

    wind: float = 0.0
    rain: bool = False
    watering: bool = False
    daylight: float = 1.0
    milestones: int = 0
    clicks: int = 0


def soundscape(world, wind_strength: float, clicks: int = 0, sun: np.ndarray | None = None) -> Soundscape:
    """The soundscape of ``world`` (an engine World) in a wind of ``wind_strength``, ``clicks`` buttons
    pressed so far, by day or night as ``sun`` shows it (the scene's sun, which at high game speeds
    stays near noon: no crickets under a bright sky; by default the world's own sun)."""
    sim = world.sim
    sun_height = float((sim.sun_direction() if sun is None else sun)[1])
    day = float(np.clip((sun_height + 0.15) / 0.35, 0.0, 1.0))  # (as the sky brightens: see render.backdrop)
    return Soundscape(float(wind_strength), bool(sim.raining()), bool(sim.state.watering), day,
                      len(world.journal.entries), int(clicks))


def loop_levels(scape: Soundscape) -> dict[str, float]:
    """How loud each loop plays (0..1, before the master volume) in ``scape``."""
    wind = 0.0 if scape.wind < WIND_QUIET else 0.15 + 0.65 * min(scape.wind / WIND_FULL, 1.0)
    night = (1.0 - scape.daylight) ** 2
    return {"wind": wind, "rain": 0.7 * scape.rain, "pour": 0.8 * scape.watering, "night": 0.35 * night}


@cache
def _made() -> dict[str, np.ndarray]:
    """Every sound, synthesised once a run (a third of a second of numpy; a kiosk makes many games)."""
    return {"wind": synth.wind(), "rain": synth.rain(), "pour": synth.pour(), "night": synth.crickets(),
            "chime": synth.chime(), "click": synth.click(), **{f"bird{k}": synth.bird(5 + k) for k in range(BIRDS)}}


class Audio:
    """Plays the soundscape (see module docstring). ``volume`` 0..1 and ``muted`` are the player's."""

    def __init__(self, volume: float = 0.7, muted: bool = False, seed: int = 29) -> None:
        self.volume, self.muted = float(np.clip(volume, 0.0, 1.0)), bool(muted)
        self.rng = np.random.default_rng(seed)
        self.levels = dict.fromkeys(LOOPS, 0.0)  # each loop's level now (0 = stopped), master volume applied
        self.heard: list[str] = []  # one-shots started (birds, chimes, clicks), latest last
        self.milestones: int | None = None  # (None until the first soundscape: a loaded journal is not news)
        self.clicks: int | None = None
        self.mixer = None
        self.sounds: dict = {}
        self.channels: dict = {}
        self._start_mixer()

    def _start_mixer(self) -> None:
        """Open pygame's mixer and make the sounds; if no mixer can start, stay silent."""
        try:
            if not pygame.mixer.get_init():
                pygame.mixer.init(synth.RATE, -16, 2, 4096)  # (few wake-ups of the mixing thread)
            pygame.mixer.set_num_channels(len(LOOPS) + 6)
            pygame.mixer.set_reserved(len(LOOPS))
            make = pygame.sndarray.make_sound
        except (pygame.error, NotImplementedError):
            return
        rate = pygame.mixer.get_init()[0]
        for name, sound in _made().items():
            if rate != synth.RATE:  # (the mixer was opened at another rate by someone else)
                sound = np.interp(np.arange(0, len(sound), synth.RATE / rate), np.arange(len(sound)), sound)
            self.sounds[name] = make(synth.stereo16(sound))
        self.channels = {name: pygame.mixer.Channel(k) for k, name in enumerate(LOOPS)}
        self.mixer = pygame.mixer

    @property
    def master(self) -> float:
        """The volume every sound is played at (0 when muted)."""
        return 0.0 if self.muted else self.volume

    def hear(self, scape: Soundscape, seconds: float) -> None:
        """Play what ``scape`` sounds like for the next ``seconds`` (called once a frame)."""
        for name, level in loop_levels(scape).items():
            self._loop(name, level * self.master)
        if self.rng.random() < BIRD_RATE * scape.daylight**2 * (not scape.rain) * seconds:
            self.play(f"bird{int(self.rng.integers(BIRDS))}", 0.5)
        if self.milestones is not None and scape.milestones > self.milestones:
            self.play("chime", 0.8)
        if self.clicks is not None and scape.clicks > self.clicks:
            self.click()
        self.milestones, self.clicks = scape.milestones, scape.clicks

    def click(self) -> None:
        """A button's tick."""
        self.play("click", 0.5)

    def play(self, name: str, level: float) -> None:
        """Start the one-shot ``name`` at ``level`` (of the master volume) on a free channel."""
        self.heard = [*self.heard[-15:], name]
        if self.mixer is not None and self.master > 0.0:
            channel = self.sounds[name].play()
            if channel is not None:
                channel.set_volume(level * self.master)

    def _loop(self, name: str, level: float) -> None:
        """Keep loop ``name`` playing at ``level`` (start it, change its volume, or fade it out at 0)."""
        was, self.levels[name] = self.levels[name], level
        if self.mixer is None:
            return
        channel = self.channels[name]
        if level > 0.0:
            if was <= 0.0 or not channel.get_busy():
                channel.play(self.sounds[name], loops=-1, fade_ms=FADE_MS)
            channel.set_volume(level)
        elif was > 0.0:
            channel.fadeout(FADE_MS)

    def playing(self, name: str) -> bool:
        """Whether loop ``name``'s channel is playing (through the mixer; False without one)."""
        return self.mixer is not None and bool(self.channels[name].get_busy())

    def set_volume(self, volume: float, muted: bool | None = None) -> None:
        """The player's volume (0..1) and, if given, mute; the loops follow at the next :meth:`hear`."""
        self.volume = float(np.clip(volume, 0.0, 1.0))
        if muted is not None:
            self.muted = bool(muted)
