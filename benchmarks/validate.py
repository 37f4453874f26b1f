"""The plant model beside outside references computed in the same run, each with its literature range and source.

Run: python -m benchmarks.validate [--days 14] [--markdown] [--write docs/plant.md]

1. **The sun.** The model's clear-sky daily irradiation (engine/life/plant/solar.py) at midsummer and the
   equinox against the top-of-atmosphere daily insolation (closed form: FAO-56 eq. 21, its own declination) and
   FAO-56's clear-sky radiation (0.75 x that: Allen et al. 1998, eq. 37); the lab's game sun (a place and date
   mapped onto the orbit's sliders) against the real sun's daily PAR.
2. **The leaf.** Each species' non-rectangular hyperbola (engine/life/plant/photosynthesis.py) beside the negative
   exponential light response of the SUCROS crop models (Goudriaan & van Laar 1994, "Modelling potential crop
   growth processes") with the same Amax and quantum efficiency, and its light compensation point.
3. **The plant.** Both species grown watered in an endless summer for DAYS game days (14: half a year on the
   declared time scale, a growing season), then their quantities in real units against literature ranges;
   and how long each lives in waterlogged soil (the can always held) against flood-tolerance classes.
Every row says whether the model lies within 2x of the range ("ok"), and the table can be written into
docs/plant.md between its markers (tests/test_validate.py checks the sun and leaf rows there against a run).
"""

from __future__ import annotations

import argparse
import math
import time
from dataclasses import dataclass
from pathlib import Path

from arbor.engine.life.experiment.measure import measure, place_day_par, root_shoot
from arbor.engine.life.plant import carbon, photosynthesis, solar
from arbor.engine.life.plant.carbon import full_ppfd
from arbor.engine.life.rules.rules import Rules, load_rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem
from arbor.game.paths import ASSETS

SHADE = 0.75  # the shade the plant rows' second run grows in (sun and shade leaves)
MARKERS = ("<!-- validate-table -->\n", "<!-- /validate-table -->\n")
FAO = "Allen et al. 1998, FAO-56 eq. 21 and 37"


@dataclass
class Row:
    """One quantity: the model's value beside the reference's (a number or a range) and where it comes from."""

    quantity: str
    unit: str
    model: float
    low: float
    high: float
    source: str

    def ok(self) -> bool:
        """Within 2x of the range (between low / 2 and high x 2)."""
        return self.low / 2 <= self.model <= self.high * 2

    def cells(self) -> list[str]:
        """The row as table cells."""
        ref = f"{self.low:.3g}" if self.low == self.high else f"{self.low:.3g}-{self.high:.3g}"
        return [self.quantity, self.unit, f"{self.model:.3g}", ref, "ok" if self.ok() else "OUT", self.source]


def top_of_atmosphere(latitude: float, day: int, constant: float) -> float:
    """Daily insolation at the top of the atmosphere (MJ per m²): FAO-56 eq. 21 with its own declination (eq. 24)
    and Earth-Sun distance (eq. 23), independent of the model's solar.py."""
    dec = 0.409 * math.sin(2 * math.pi * day / 365 - 1.39)
    phi = math.radians(latitude)
    sunset = math.acos(max(-1.0, min(1.0, -math.tan(phi) * math.tan(dec))))
    distance = 1 + 0.033 * math.cos(2 * math.pi * day / 365)
    return 86400 / math.pi * constant * 1e-6 * distance * (sunset * math.sin(phi) * math.sin(dec)
                                                           + math.cos(phi) * math.cos(dec) * math.sin(sunset))


def sun_rows() -> list[Row]:
    """The model's clear sky against FAO-56 and the game's sun against the model's real sun."""
    rules = Rules().sun
    rows = []
    for lat in (0, 30, 45, 60):
        toa = top_of_atmosphere(lat, 172, rules.solar_constant)
        rows.append(Row(f"clear-sky daily irradiation, {lat} N midsummer", "MJ/m²/day",
                        solar.daily_global(lat, 172, rules), 0.75 * toa, 0.75 * toa, f"{FAO} (TOA {toa:.1f})"))
    for lat, day in ((0, 80), (45, 80), (45, 355)):
        toa = top_of_atmosphere(lat, day, rules.solar_constant)
        rows.append(Row(f"clear-sky daily irradiation, {lat} N day {day}", "MJ/m²/day",
                        solar.daily_global(lat, day, rules), 0.75 * toa, 0.75 * toa, f"{FAO} (TOA {toa:.1f})"))
    for lat in (0, 30, 60):
        real = solar.daily_par(lat, 172, rules)
        rows.append(Row(f"the game's sun (lab place and date), {lat} N midsummer", "MJ PAR/m²/day",
                        place_day_par(lat, 172),
                        real, real, "solar.daily_par of the real sun, same place and date"))
    return rows


def leaf_rows(species: dict[str, dict[str, float]]) -> list[Row]:
    """Each species' light response against SUCROS's negative exponential, and its compensation point."""
    rules = Rules()
    rows = []
    for name, constants in species.items():
        t = photosynthesis.leaf_traits(constants, rules)
        for ppfd in (100.0, 500.0, 1500.0):
            model = float(photosynthesis.gross(ppfd, t))
            sucros = t.amax * (1 - math.exp(-t.quantum * ppfd / t.amax))
            rows.append(Row(f"{name}: gross assimilation at {ppfd:.0f} µmol/m²/s", "µmol CO2/m²/s", model, sucros,
                            sucros, "SUCROS negative exponential, Goudriaan & van Laar 1994"))
        tolerant = name == "game_tree"  # (the shade-tolerant species; the poplar is the pioneer)
        low, high = (5, 20) if tolerant else (20, 50)
        rows.append(Row(f"{name}: light compensation point", "µmol/m²/s", t.dark / t.quantum, low, high,
                        f"{'shade-tolerant' if tolerant else 'pioneer'} tree leaves, Lambers, Chapin & Pons 2008, "
                        "Plant Physiological Ecology"))
        full = float(photosynthesis.gross(full_ppfd(rules), t)) * photosynthesis.CH2O * 3600
        low, high = (0.6, 1.2) if tolerant else (1.6, 2.8)
        rows.append(Row(f"{name}: a leaf's gross maximum", "g CH2O/m²/h", full, low, high,
                        "Amax 6-10 (tolerant) or 15-25 µmol/m²/s (pioneer), Walters, Kruger & Reich 1993"))
    return rows


def grow(system, days: float, seed: int = 3, shade: float = 0.0) -> tuple[World, float]:
    """A tree watered between 0.55 and 0.75 in an endless summer under the default sun (``shade`` of it removed) for
    ``days``; returns the world and the PAR its leaves intercepted (MJ, on the declared time scale)."""
    rules = load_rules(ASSETS / "rules.toml", pace="demo")
    rules.seasons.enabled = False
    rules.sun.shade = shade
    world = World(system, rules, seed=seed)
    world.apply(Action.ORBIT_HEIGHT, 0.35)
    world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
    dt, real, caught = 0.5, photosynthesis.real_seconds(rules), 0.0
    for _ in range(round(days * 2 * math.pi / rules.sun.speed / dt)):
        s = world.sim.state
        world.apply(Action.WATER, float(s.water_meter < 0.75 if s.watering else s.water_meter < 0.55))
        world.step(dt)
        caught += world.carbon.leaf_area * world.tree.mean_light * world.sim.par() * dt * real * 1e-6
    return world, caught


PLANT = {  # quantity: (unit, tolerant range, pioneer range, source)
    "height": ("m", (0.1, 0.5), (1.0, 3.0), "first-season saplings: shade-tolerant 0.1-0.5 m, a poplar from a cutting "
               "1-3 m (Dickmann et al. 2001, Poplar Culture in North America)"),
    "biomass": ("g", (5, 200), (100, 1000), "above ground after a season: tolerant seedlings 5-200 g, a poplar under "
                "1 kg (Walters et al. 1993; Dickmann et al. 2001)"),
    "root_shoot": ("g/g", (0.2, 0.5), (0.2, 0.5), "young trees, watered: Poorter et al. 2012, Biomass allocation to "
                   "leaves, stems and roots"),
    "h_d": ("m/m", (50, 100), (50, 100), "saplings' height:diameter, 50-100 (Wang et al. 1998)"),
    "leaf_share": ("%", (20, 40), (20, 40), "leaves' share of above-ground mass in saplings (Poorter et al. 2012)"),
    "lue": ("g/MJ PAR", (1, 3), (1, 3), "dry matter per MJ of intercepted PAR (Monteith 1977; Cannell 1989)"),
    "wood_density": ("kg/m³", (550, 700), (350, 450), "maple or poplar wood, Chave et al. 2009, Global wood density "
                     "database"),
}


def dry_matter(world: World) -> float:
    """Dry matter (g) the tree made since planting: what it built (leaves, wood, roots) and the sugar its pool
    gained (non-structural carbohydrate is dry matter too; the seed's reserve was not made by the leaves)."""
    return world.carbon.built + world.carbon.pool - world.rules.carbon.seed_reserve


def plant_rows(species: dict[str, object], days: float) -> list[Row]:
    """Both species' quantities after ``days`` of the default care, against PLANT's ranges."""
    rows = []
    for name, system in species.items():
        world, caught = grow(system, days)
        m = measure(world)
        tolerant = name == "game_tree"
        leaf = world.carbon.leaf_area * carbon.leaf_mass(world.rules, world.leaf_light()) / 1000.0
        values = {"height": m["height"], "biomass": m["biomass"] * 1000, "root_shoot": root_shoot(world.carbon),
                  "h_d": m["height"] / max(m["girth"] / 100, 1e-9), "leaf_share": 100 * leaf / max(m["biomass"], 1e-9),
                  "lue": dry_matter(world) / max(caught, 1e-9),
                  "wood_density": float(system.constants.get("WD", world.rules.carbon.wood_density / 1000))}
        for key, (unit, tol, pio, source) in PLANT.items():
            low, high = tol if tolerant else pio
            rows.append(Row(f"{name}: {key.replace('_', ' ')} after {days:g} game days "
                            f"({days * photosynthesis.real_days(world.rules):.0f} real)", unit, values[key], low,
                            high, source))
        shaded, _ = grow(system, days, shade=SHADE)
        sla = carbon.leaf_mass(world.rules, world.leaf_light()) / carbon.leaf_mass(shaded.rules, shaded.leaf_light())
        rows.append(Row(f"{name}: specific leaf area of new leaves, {SHADE:.0%} shade over full sun", "m²/g / m²/g",
                        sla, 1.3, 2.0, "leaves grown in deep shade have about half to two thirds of a sun leaf's mass "
                        "per area (Poorter et al. 2009, Causes and consequences of variation in leaf mass per area)"))
    return rows


def drowned_days(system, most: float = 20.0) -> float:
    """Real days (on the declared time scale) a tree lives with the can always held (waterlogged soil), at most
    ``most`` game days."""
    rules = load_rules(ASSETS / "rules.toml", pace="demo")
    rules.seasons.enabled = False
    world = World(system, rules, seed=3)
    world.apply(Action.WATER, 1.0)
    dt = 0.5
    for _ in range(round(most * 2 * math.pi / rules.sun.speed / dt)):
        world.step(dt)
        if not world.sim.state.alive:
            break
    return world.sim.state.sun_turns * photosynthesis.real_days(rules)


def flood_rows(species: dict[str, object]) -> list[Row]:
    """How long each species lives in waterlogged soil against flood-tolerance classes."""
    ranges = {"game_tree": ((7, 28), "flood-intolerant seedlings (a maple's) 1-4 weeks"),
              "game_poplar": ((30, 120), "flood-tolerant seedlings (many poplars') months")}
    return [Row(f"{name}: survival in waterlogged soil", "real days", drowned_days(system), *ranges[name][0],
                f"{ranges[name][1]}, Kozlowski 1997, Responses of woody plants to flooding and salinity")
            for name, system in species.items()]


def table(rows: list[Row]) -> str:
    """The rows as a markdown table."""
    lines = ["| quantity | unit | model | reference | within 2x | source |", "|---|---|---|---|---|---|"]
    lines += ["| " + " | ".join(row.cells()) + " |" for row in rows]
    return "\n".join(lines) + "\n"


def write(doc: Path, text: str) -> None:
    """Put ``text`` between docs/plant.md's markers."""
    start, end = MARKERS
    body = doc.read_text(encoding="utf-8")
    head, _, rest = body.partition(start)
    doc.write_text(head + start + text + end + rest.partition(end)[2], encoding="utf-8")


def main() -> None:
    """Run the references and the model; print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--days", type=float, default=14.0)
    parser.add_argument("--markdown", action="store_true", help="print the table as markdown")
    parser.add_argument("--write", type=Path, help="write the markdown table into this file between its markers")
    args = parser.parse_args()
    start = time.perf_counter()
    systems = {n: load_lsystem(ASSETS / "lsystems" / f"{n}.lsys") for n in ("game_tree", "game_poplar")}
    rows = sun_rows() + leaf_rows({n: s.constants for n, s in systems.items()}) + plant_rows(systems, args.days)
    rows += flood_rows(systems)
    if args.markdown or args.write:
        text = table(rows)
        print(text)
        if args.write:
            write(args.write, text)
    else:
        for row in rows:
            q, unit, model, ref, ok, source = row.cells()
            print(f"{q:62} {model:>9} {ref:>13} {unit:15} {ok:4} {source}")
    out = sum(not r.ok() for r in rows)
    print(f"{len(rows) - out} of {len(rows)} within 2x of their references ({time.perf_counter() - start:.0f} s)")


if __name__ == "__main__":
    main()
