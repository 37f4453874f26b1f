"""What the lab and the sweeps measure on a tree, in physical units (docs/columns.md lists every column).

Lengths in metres (the scene's metre, engine/base/units.py), the trunk's girth in cm, areas in m², mass
in kg, sugar in g (the plant's carbon budget, engine/life/plant/carbon.py). Meters and wilt are not one
instant: :class:`Meters` keeps their mean, minimum and maximum since the last sample, so a meter that
swings within a day is not caught at one phase of its swing.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass, field

import numpy as np

from arbor.engine.base.units import METRE
from arbor.engine.life.form.interpret import grown_turtle
from arbor.engine.life.plant import carbon, photosynthesis, solar
from arbor.engine.life.world.world import World

SWUNG = ("sun", "water", "wilt")  # sampled as mean, min and max since the last sample
METRICS = ("height", "width", "offset", "girth", "modules", "leaves", "density", "shed", "roots",
           *(f"{m}{s}" for m in SWUNG for s in ("", "_min", "_max")), "alive", "day_of_death", "fruit",
           "biomass", "leaf_area", "lai", "light_share", "light_day", "net_carbon", "pool", "root_shoot", "pruned",
           "real_days", "par_day")
UNITS = {"height": "m", "width": "m", "offset": "m", "girth": "cm", "modules": "count", "leaves": "count",
         "density": "per m³", "shed": "count", "roots": "m", **{f"{m}{s}": "0..1" for m in SWUNG
                                                               for s in ("", "_min", "_max")},
         "alive": "1 or 0", "day_of_death": "game day", "fruit": "count", "biomass": "kg", "leaf_area": "m²",
         "lai": "m² per m²", "light_share": "0..1", "light_day": "m² x h per day", "net_carbon": "g", "pool": "g",
         "root_shoot": "g per g", "pruned": "count", "real_days": "real days", "par_day": "MJ per day"}


@dataclass
class Meters:
    """The meters and wilt since the last sample (mean, min, max), light caught, and the day of death."""

    sums: dict[str, float] = field(default_factory=lambda: dict.fromkeys(SWUNG, 0.0))
    low: dict[str, float] = field(default_factory=lambda: dict.fromkeys(SWUNG, math.inf))
    high: dict[str, float] = field(default_factory=lambda: dict.fromkeys(SWUNG, -math.inf))
    seconds: float = 0.0
    light: float = 0.0  # m² of full-sun-lit leaf x s since the last sample
    lit: float = 0.0  # the leaves' mean light x the sun's strength x s since the last sample
    shine: float = 0.0  # the sun's strength x s since the last sample
    died: float = math.nan  # game day of death
    # the light caught in each step of the last game day (turns of the sun, m² x s): light_day sums it
    day: deque = field(default_factory=deque)
    day_light: float = 0.0  # m² of full-sun-lit leaf x s over the steps in ``day``
    day_turns: float = 0.0  # turns of the sun the steps in ``day`` span (1 once a whole day has passed)

    def add(self, world: World, dt: float) -> None:
        """Book one step of ``dt`` seconds of ``world``."""
        s = world.sim.state
        for key, value in zip(SWUNG, (s.sun_meter, s.water_meter, s.wilt), strict=True):
            self.sums[key] += value * dt
            self.low[key] = min(self.low[key], value)
            self.high[key] = max(self.high[key], value)
        self.seconds += dt
        shine = world.sim.sunshine()
        caught = world.carbon.leaf_area * world.tree.mean_light * shine * dt
        self.light += caught
        self._remember_day(s.sun_turns, caught, s.sun_speed * dt / (2 * math.pi))
        self.lit += (world.tree.mean_light if world.carbon.leaf_area > 0 else 0.0) * shine * dt
        self.shine += shine * dt
        if not s.alive and math.isnan(self.died):
            self.died = s.sun_turns

    def _remember_day(self, turns: float, caught: float, step: float) -> None:
        """Keep the light caught over the last turn of the sun (a sliding game day of ``step``-turn steps)."""
        self.day.append((turns, caught, step))
        self.day_light += caught
        self.day_turns += step
        while self.day and self.day[0][0] <= turns - 1.0:
            _, light, old = self.day.popleft()
            self.day_light -= light
            self.day_turns -= old

    def light_day(self, world: World) -> float:
        """The light caught over the last game day (m² of full-sun-lit leaf x game hours): a daily total
        whatever the sampling; before a whole day has passed, the part so far scaled up to a day."""
        if not self.day_turns > 0:
            return 0.0
        day_seconds = 2 * math.pi / world.sim.state.sun_speed
        return self.day_light / day_seconds * 24.0 / min(self.day_turns, 1.0)

    def reset(self) -> None:
        """Start the next interval (the day of death is kept)."""
        self.sums, self.seconds, self.light, self.lit, self.shine = dict.fromkeys(SWUNG, 0.0), 0.0, 0.0, 0.0, 0.0
        self.low, self.high = dict.fromkeys(SWUNG, math.inf), dict.fromkeys(SWUNG, -math.inf)

    def swung(self, world: World) -> dict[str, float]:
        """Mean, min and max of each meter since the last sample (the instant, at the first sample)."""
        s = world.sim.state
        now = dict(zip(SWUNG, (s.sun_meter, s.water_meter, s.wilt), strict=True))
        out = {}
        for key in SWUNG:
            timed = self.seconds > 0
            out[key] = self.sums[key] / self.seconds if timed else now[key]
            out[f"{key}_min"] = self.low[key] if timed else now[key]
            out[f"{key}_max"] = self.high[key] if timed else now[key]
        return out


def measure(world: World, meters: Meters | None = None) -> dict[str, float]:
    """Every metric of METRICS for ``world`` now (see UNITS and docs/columns.md)."""
    meters = meters or Meters()
    turtle = grown_turtle(world.tree.lstring, world.clocks(), world.tree.geometry_constants)  # (no meshes)
    segs, leaves = turtle.segments, turtle.leaves
    shape = crown_shape(segs, leaves)
    big = leaves.size > 0.05 * leaves.size.max() if len(leaves) else np.zeros(0, bool)
    on_tree = len(np.unique(leaves.module[big]))
    box = np.ptp(leaves.position[big], axis=0) / METRE if big.any() else np.zeros(3)
    side = np.array([0.0, 0.0, 1.0]) if world.rules.sun.side >= 0 else np.array([0.0, 0.0, -1.0])
    s, budget = world.sim.state, world.carbon
    width = shape["width"] / METRE
    return {"height": shape["height"] / METRE, "width": width, "offset": float(shape["centroid"] @ side) / METRE,
            "girth": float(2 * segs.radius[0]) / METRE * 100 if len(segs) else 0.0,
            "modules": float(len(world.tree.lstring)), "leaves": float(on_tree),
            "density": on_tree / float(np.prod(np.maximum(box, 0.05))), "shed": float(world.tree.shed_total),
            "roots": world.roots.length() / METRE, **meters.swung(world), "alive": float(s.alive),
            "day_of_death": meters.died, "fruit": float(world.tree.lstring.count("O")),
            "biomass": biomass(world, segs), "leaf_area": budget.leaf_area,
            "lai": budget.leaf_area / max(math.pi * (width / 2) ** 2, 0.01),
            "light_share": meters.lit / meters.shine if meters.shine > 0 else world.tree.mean_light,
            "light_day": meters.light_day(world),
            "net_carbon": budget.fixed - budget.respired, "pool": budget.pool, "root_shoot": root_shoot(budget),
            "pruned": float(sum(v for _, kind, v in world.journal.entries if kind == "pruned")),
            **real_units(world, meters)}


def real_units(world: World, meters: Meters) -> dict[str, float]:
    """The declared time scale's view (engine/life/rules/schema.py, seasons.real_year): the real days the game
    days so far stand for, and the PAR the leaves intercepted over the last game day as MJ a real day (a game
    day is one representative day of the span it stands for: m² x hours of full sun x the full sun's PAR)."""
    full = solar.full_par(world.rules.sun)  # W/m² of the sun's strength 1
    return {"real_days": world.sim.state.sun_turns * photosynthesis.real_days(world.rules),
            "par_day": meters.light_day(world) * 3600.0 * full * 1e-6}


def root_shoot(budget: carbon.CarbonBudget) -> float:
    """Root:shoot ratio of what the tree has built since planting: sugar into roots over sugar into
    leaves, shoots and wood (g per g; 0 before anything above ground is built)."""
    shoot = budget.built - budget.roots_built
    return budget.roots_built / shoot if shoot > 0 else 0.0


def biomass(world: World, segs) -> float:
    """Above-ground biomass (kg): the wood's volume (every segment a cylinder) x the species' wood density,
    plus the leaf area x the leaf mass per area of the leaves it grows in its light now (carbon.leaf_mass)."""
    length = np.linalg.norm(segs.end - segs.start, axis=1) if len(segs) else np.zeros(0)
    volume = float((np.pi * segs.radius**2 * length).sum()) / METRE**3 if len(segs) else 0.0
    density = carbon.wood_density(world.tree.system.constants, world.rules)
    leaf = carbon.leaf_mass(world.rules, world.leaf_light())  # (g per m² of the leaves it grows now)
    return (volume * density + world.carbon.leaf_area * leaf) / 1000.0


def crown_shape(segs, leaves) -> dict:
    """Height (top of the wood), crown width (largest horizontal extent of the leaves) and the leaves'
    centroid relative to the trunk's base (x, 0, z), in scene units."""
    height = float(segs.end[:, 1].max()) if len(segs) else 0.0
    if len(leaves) == 0:
        return {"height": height, "width": 0.0, "centroid": np.zeros(3)}
    base = segs.start[0] if len(segs) else np.zeros(3)
    flat = leaves.position[:, [0, 2]]
    width = float(np.ptp(flat, axis=0).max())
    centroid = leaves.position.mean(axis=0) - base
    centroid[1] = 0.0
    return {"height": height, "width": width, "centroid": centroid}


def place_day_par(latitude: float, day_of_year: int, steps: int = 2000) -> float:
    """The daily PAR (MJ per m² in a real day) of the game's sun set for a place and date the way the lab
    sets it (the day length sets the orbit's height, the noon elevation its side; engine/life/experiment/
    schema.py): its PAR summed over one turn, to hold against the real sun's (solar.daily_par)."""
    from arbor.engine.life.experiment.lab import Regime, orbit_height, regime_rules
    from arbor.engine.life.plant.sim import Simulation
    from arbor.engine.life.rules.rules import Rules

    base = Rules()
    base.seasons.enabled = False
    place = Regime("place", latitude=latitude, day_of_year=day_of_year)
    rules = regime_rules(base, place)
    sim = Simulation(rules)
    sim.set_orbit_height(orbit_height(place, rules))
    total = 0.0
    for k in range(steps):
        sim.state.sun_angle = 2 * math.pi * (k + 0.5) / steps
        total += sim.par()
    return total / steps * 86400 * 1e-6

