"""The tree's carbon budget: what its leaves fix from the light they really catch, what living tissue
costs to keep, and what is left to build with.

A canopy model in the manner of the functional-structural plant models (LIGNUM by Perttunen et al.;
GreenLab by de Reffye and Hu): every leaf fixes sugar by its species' light response (a non-rectangular
hyperbola, engine/life/plant/photosynthesis.py) to the photons that reach it (the sun's PAR at its
elevation, engine/life/plant/solar.py, times the leaf's light from the shadow grid, engine/life/plant/light.py),
times how far its stomata are open (they close smoothly as the soil dries, and as drowned roots fail).
Leaves and living wood respire: the leaves by their species' dark respiration per m², the wood in
proportion to its sapwood, which by the pipe model (Shinozaki et
al.) is the conducting cross-section that carries the leaves above it. What is left goes into a pool,
spent by priority (Lacointe's "sink priority": leaves and shoots first, then girth, then roots),
except ``keep_time`` of upkeep kept for the nights; the pool holds at most ``reserve_time`` of the tree's
summer upkeep. A pool that stays empty while the
balance is negative for ``starve_time`` starves the tree: it wilts, and a tree that stays fully wilted
dies, so a leafless tree cannot live on.

Units: sugar in grams (g), leaf area in m², wood in m³ (scene units through METRE), time in game
seconds; a leaf's rates are real (µmol per m² per s), made the game's by the declared time scale
(photosynthesis.real_seconds); the rules' [carbon] table gives the rest at the demo pace.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from arbor.engine.base.units import METRE
from arbor.engine.life.form.interpret import APEX, BLOSSOM, CLUSTER_AREA, FRUIT, LEAF, LEAF_ASPECT
from arbor.engine.life.plant import photosynthesis, soil, solar
from arbor.engine.life.plant.photosynthesis import LeafTraits
from arbor.engine.life.rules.rules import Rules
from arbor.engine.lsystem.lstring import LString

AREA = 1.0 / METRE**2  # m² per scene unit²
VOLUME = 1.0 / METRE**3  # m³ per scene unit³
# m³ of wood per scene unit of length x pipe "area": the pipe model's areas are squared radii (the turtle draws
# a radius of their square root), so a piece's cross-section is pi x that
WOOD = math.pi * VOLUME


@dataclass
class Canopy:
    """What a light reading tells the budget: the leaves' area and the light on it, and the sapwood."""

    leaf_area: float  # m² of leaves on the tree
    lit_area: float  # m² of leaf x the light that reaches it (0..1): what photosynthesis works with
    sapwood: float  # m³ of conducting wood (pipe area x length over every grown internode)
    leaf_areas: np.ndarray | None = None  # m² of each leaf (None: the light on them is lit_area's alone)
    leaf_lights: np.ndarray | None = None  # the light reaching each leaf (0..1)


@dataclass
class CarbonBudget:
    """One tree's sugar: the pool, how long it has been starving, and running totals for the lab."""

    pool: float = 0.0  # g of sugar in store
    starving: float = 0.0  # s the pool has been empty with upkeep unpaid
    fixed: float = 0.0  # g fixed since planting
    respired: float = 0.0  # g respired since planting
    built: float = 0.0  # g built into leaves, shoots, wood and roots since planting
    roots_built: float = 0.0  # g of it built into roots (root:shoot = roots_built / (built - roots_built))
    last_fixed_rate: float = 0.0  # g per s at the last reading (gross)
    last_upkeep_rate: float = 0.0  # g per s at the last reading (maintenance respiration)
    vigour: float = 1.0  # share of the shoots' growth the pool paid for at the last rewrite
    leaf_area: float = 0.0  # m² at the last reading
    sapwood: float = 0.0  # m³ at the last reading
    fill_at_next_reading: bool = False  # a tree from before the carbon budget: its pool starts full
    stored: float = 0.0  # s of upkeep kept from growth beyond keep_time at the last reading (seasons.stores)
    root_balance: float = 0.0  # the functional balance's need over supply at the last reading (root_balance)
    # (not saved, set again at every reading: plain class attributes, not fields)
    leaf_cost = 0.0  # g per m² of leaf per s: its leaves' dark respiration (0: the rules' default leaf)
    full_rate = 0.0  # g per m² per s a fully lit, open leaf of the rules' reference leaf fixes under the zenith sun

    @classmethod
    def for_seedling(cls, rules: Rules) -> CarbonBudget:
        """A new sapling's budget: the seed's reserve."""
        return cls(pool=rules.carbon.seed_reserve)

    def capacity(self, rules: Rules) -> float:
        """The most the pool can fill to: ``reserve_time`` of the tree's summer upkeep."""
        return rules.carbon.reserve_time * self.upkeep_rate(rules)

    def upkeep_rate(self, rules: Rules, activity: float = 1.0) -> float:
        """Maintenance respiration (g per s) of the leaves and sapwood last measured and of the roots built (the
        fine roots the leaves keep at root_respiration, the coarse ones at coarse_root_share of it), at
        ``activity`` (0..1)."""
        c = rules.carbon
        leaf = self.leaf_cost or float(photosynthesis.grams(photosynthesis.leaf_traits({}, rules).dark, rules))
        fine = min(self.roots_built, c.fine_root_leaf * c.leaf_mass * self.leaf_area)
        living = fine + c.coarse_root_share * (self.roots_built - fine)  # (g of root respiring as fine roots)
        roots = float(photosynthesis.grams(c.root_respiration * 1e-3, rules)) * living
        return (leaf * self.leaf_area + c.wood_respiration * self.sapwood + roots) * activity

    def live(self, rules: Rules, seconds: float, shine: float, stomata: float, activity: float,
             canopy: Canopy | None = None, bare_starves: bool = False, traits: LeafTraits | None = None) -> float:
        """Book ``seconds`` of photosynthesis and respiration; returns the net sugar (g, may be negative).

        ``canopy`` is this reading's measurement (None at night: the last one respires on); ``shine``
        the sun's strength 0..1 (its PAR against the zenith sun's); ``stomata`` how open the leaves are 0..1;
        ``activity`` how awake the tree is (1 in the growing season, the dormant share in winter rest);
        ``traits`` the species' leaves (None: the rules' default leaf). The tree starves while its upkeep
        goes unpaid, and, when ``bare_starves`` (a season in which it should be in leaf), while it has no
        leaves at all to earn with."""
        if not seconds > 0:
            return 0.0
        if canopy is not None:
            self.leaf_area, self.sapwood = canopy.leaf_area, canopy.sapwood
            if self.fill_at_next_reading:
                self.pool, self.fill_at_next_reading = self.capacity(rules), False
        traits = traits or photosynthesis.leaf_traits({}, rules)
        self.leaf_cost = float(photosynthesis.grams(traits.dark, rules))
        reference = photosynthesis.gross(full_ppfd(rules), photosynthesis.leaf_traits({}, rules))
        self.full_rate = float(photosynthesis.grams(reference, rules))
        gross = assimilation(canopy, shine, traits, rules) * min(max(stomata, 0.0), 1.0)
        upkeep = self.upkeep_rate(rules, activity)
        self.last_fixed_rate, self.last_upkeep_rate = gross, upkeep
        net = (gross - upkeep) * seconds
        self.fixed += gross * seconds
        self.respired += upkeep * seconds
        pool = self.pool + net
        starving = pool < 0 or (bare_starves and self.leaf_area <= 0)
        self.starving = self.starving + seconds if starving else max(self.starving - seconds, 0.0)
        self.pool = min(max(pool, 0.0), max(self.capacity(rules), self.pool))  # (a seed may hold more)
        return net

    def caught(self) -> float:
        """The sugar the leaves fixed at the last reading per m², against fully lit, open leaves of the rules'
        reference leaf (carbon.amax) under the zenith sun, at most 1 (0 with no leaves): a species with a higher
        Amax earns more from the same light."""
        full = self.full_rate * self.leaf_area
        return min(self.last_fixed_rate / full, 1.0) if full > 0 else 0.0

    def spare(self, rules: Rules) -> float:
        """Sugar that may be spent on growth: the pool above what is kept for upkeep (``keep_time`` of it, and
        the season's stores: ``stored``)."""
        return max(self.pool - (rules.carbon.keep_time + self.stored) * self.upkeep_rate(rules), 0.0)

    def drive(self, rules: Rules) -> float:
        """How fast the pool lets the tree build, against the clock's pace (extern C): the pool's fill (its spare
        sugar over its capacity) over ``growth_fill``: 1 at that fill, in proportion below it (an empty pool
        builds nothing), up to ``growth_most`` above it (a full pool builds more). Growth is set by the carbon
        the leaves earn, not by the clock (Thornley 1972's substrate-driven growth)."""
        c = rules.carbon
        capacity = self.capacity(rules) * c.growth_fill
        spare = self.spare(rules)
        return min(spare / capacity, c.growth_most) if capacity > 0 else (c.growth_most if spare > 0 else 0.0)

    def shoots_share(self, rules: Rules, demand: float, roots_due: float) -> float:
        """Extern C: how fast the shoots grow against the clock's pace, for ``demand`` g of dry mass at that pace:
        the pool's :meth:`drive`, and no more than the spare sugar left once the roots' due (``roots_due`` g) is
        kept for them (``growth_cost`` g of sugar a gram)."""
        cost = rules.carbon.growth_cost
        spare = max(self.spare(rules) - roots_due * cost, 0.0)
        return min(self.drive(rules), spare / max(demand * cost, 1e-12))

    def share(self, rules: Rules, demand: float) -> float:
        """The share 0..1 of growth that would build ``demand`` g of dry mass at full speed the pool pays now: the
        pool's :meth:`drive` (at most 1), and no more than its spare sugar (``growth_cost`` g a gram)."""
        cost = demand * rules.carbon.growth_cost
        return min(self.spare(rules) / cost, self.drive(rules), 1.0) if cost > 0 else 1.0

    def fund(self, rules: Rules, demand: float, driven: bool = True) -> float:
        """Spend on growth that would build ``demand`` g of dry mass at full speed: returns the share 0..1 the
        pool pays (and takes it); ``driven``: no more than the pool's :meth:`drive` (else as far as its spare
        sugar goes: the roots' functional balance)."""
        share = self.share(rules, demand) if driven else min(self.spare(rules) / max(
            demand * rules.carbon.growth_cost, 1e-12), 1.0)
        self.spend(rules, share * max(demand, 0.0))
        return share

    def spend(self, rules: Rules, grams: float) -> None:
        """Take what was built (``grams`` of dry mass in leaves, shoots, wood, roots) out of the pool: its sugar
        and the respiration that built it, ``growth_cost`` g of sugar a gram."""
        grams = max(grams, 0.0)
        self.pool = max(self.pool - grams * rules.carbon.growth_cost, 0.0)
        self.built += grams


def full_ppfd(rules: Rules) -> float:
    """The photon flux (µmol per m² per s) of the sun's strength 1: PAR under a clear sky's zenith sun."""
    return solar.full_par(rules.sun) * rules.sun.par_photons


def assimilation(canopy: Canopy | None, shine: float, traits: LeafTraits, rules: Rules) -> float:
    """Gross sugar (g per game s) the leaves of ``canopy`` fix with open stomata at the sun's strength ``shine``:
    each leaf by the light response to its own photons, summed over its area."""
    if canopy is None or not shine > 0:
        return 0.0
    if canopy.leaf_areas is None:  # (no leaves' lights: the mean light over the whole area)
        areas = np.array([canopy.leaf_area])
        lights = np.array([canopy.lit_area / canopy.leaf_area if canopy.leaf_area > 0 else 0.0])
    else:
        areas, lights = canopy.leaf_areas, canopy.leaf_lights
    umol = photosynthesis.gross(full_ppfd(rules) * shine * np.clip(lights, 0.0, 1.0), traits)
    return float(photosynthesis.grams(float((areas * umol).sum()), rules))


def stomata(water: float, roots: float, rules: Rules) -> float:
    """How far the leaves' stomata are open (0..1): they close smoothly as the water meter (the soil's water)
    falls (soil.opening: no threshold), times ``roots`` (0..1), how well the roots still take up water after
    waterlogging's want of oxygen (Simulation.root_health; 1 for healthy roots)."""
    return soil.opening(water, rules) * min(max(roots, 0.0), 1.0)


def canopy(leaf_area: np.ndarray, leaf_light: np.ndarray, pipe_area: np.ndarray, seg_length: np.ndarray) -> Canopy:
    """The budget's view of one light reading: leaf areas (scene units²) with their light, and the
    grown internodes' pipe areas (units²) and lengths (units)."""
    areas = np.asarray(leaf_area, float) * AREA
    lights = np.clip(np.asarray(leaf_light, float), 0.0, 1.0)
    return Canopy(float(areas.sum()), float((areas * lights).sum()), float((pipe_area * seg_length).sum()) * WOOD,
                  areas, lights)


@dataclass
class Economy:
    """One light reading's dealings with the budget: how long since the last one, the leaves' stomata, how
    awake the tree is, and what its wood costs (the tree's own sense() books and pays through it)."""

    budget: CarbonBudget
    rules: Rules
    seconds: float
    shine: float
    stomata: float = 1.0
    activity: float = 1.0
    wood_density: float = 5e5  # g per m³
    in_leaf: bool = True  # a season in which the tree should have leaves (a bare tree then starves)
    daylight: float = 1.0  # the remembered daylight against daylight_full (Simulation.light_growth): what light earns
    traits: LeafTraits | None = None  # the species' leaves (None: the rules' default leaf)
    root_balance: float = 0.0  # the functional balance's need over supply (root_balance): what the roots are due
    root_paid: float = 0.0  # the share of the roots' due the pool paid at this reading

    def book(self, measured: Canopy) -> float:
        """Photosynthesis and upkeep since the last reading, for the canopy measured now, then the roots' due;
        the net (g)."""
        net = self.budget.live(self.rules, self.seconds, self.shine, self.stomata, self.activity, measured,
                               self.in_leaf, self.traits)
        self._grow_roots()
        return net

    def rest(self, leaf_area: float) -> float:
        """A reading at night: nothing is fixed, upkeep goes on for ``leaf_area`` scene units² of leaves
        (counted from the string: no light reading is taken at night) and the sapwood last measured."""
        dark = Canopy(leaf_area * AREA, 0.0, self.budget.sapwood)
        net = self.budget.live(self.rules, self.seconds, 0.0, 0.0, self.activity, dark, self.in_leaf, self.traits)
        self._grow_roots()
        return net

    def _grow_roots(self) -> None:
        """The roots take their due by the functional balance (root_demand) first, as far as the pool's spare sugar
        goes: a balance, not the leftovers of the shoots' wood (a drier soil or a brighter crown gets more roots)."""
        demand = root_demand(self.budget, self.rules, self.seconds, self.root_balance)
        self.root_paid = self.budget.fund(self.rules, demand, driven=False)
        self.budget.roots_built += self.root_paid * demand

    def wood_share(self, volume: float) -> float:
        """The share (0..1) of ``volume`` (scene units of length x pipe area) of new rings the pool pays for now
        (and takes)."""
        return self.budget.fund(self.rules, volume * WOOD * self.wood_density)

    def pay_pipes(self, volume: float) -> None:
        """The pipe wood the new leaves need (``volume``: scene units of length x pipe area, the pipe model's
        cross-section grown since the last reading): a leaf cannot be without it, so it is built, and paid for,
        whatever the pool holds."""
        self.budget.spend(self.rules, volume * WOOD * self.wood_density)


def wood_density(constants: dict[str, float], rules: Rules) -> float:
    """A species' wood density (g per m³): its .lsys ``WD`` (kg per m³) or the rules' default."""
    return float(constants["WD"]) * 1000.0 if "WD" in constants else rules.carbon.wood_density


def leaf_mass(rules: Rules, light: float = 1.0) -> float:
    """A new leaf's mass per area (g per m²) on a tree whose leaves get ``light``, the share of the open sky's light
    (World.leaf_light): a sun leaf's ``carbon.leaf_mass`` from ``sun_leaf_light`` up, down to ``shade_lma`` of it in
    the dark, in proportion between (shade leaves are thinner: their specific leaf area is higher)."""
    c = rules.carbon
    return c.leaf_mass * (c.shade_lma + (1.0 - c.shade_lma) * min(max(light / c.sun_leaf_light, 0.0), 1.0))


def node_cost(order: np.ndarray, const: dict[str, float], rules: Rules, density: float,
              light: float = 1.0) -> np.ndarray:
    """What one new node costs at each branch ``order`` (g): a full-grown leaf cluster and the internode
    under it (its pipe for one leaf)."""
    leaf = CLUSTER_AREA * LEAF_ASPECT * const["LS"] ** 2 * AREA * leaf_mass(rules, light)
    wood = const["IL"] * const["IO"] ** order * const["TIP"] ** 2 * WOOD * density
    return leaf + wood


def shoot_demand(ls: LString, dt: float, const: dict[str, float], rules: Rules, density: float,
                 daylight: float = 1.0) -> float:
    """Sugar (g) the growing apices would build into nodes in ``dt`` of physiological time at full speed:
    each apex makes a node every plastochron ``P`` while lit above ``QG``."""
    apex = np.flatnonzero((ls.sym == APEX) & (ls.nparams == 6))
    if len(apex) == 0 or not dt > 0:
        return 0.0
    off = ls.offsets[apex]
    order, light = ls.params[off + 1], ls.params[off + 3]
    qg = const.get("QG", 0.12)
    lit = np.clip((light - qg) / max(1.0 - qg, 1e-9), 0.0, 1.0)
    nodes = dt * lit / const.get("P", 4.0)
    return float((nodes * node_cost(order, const, rules, density, daylight)).sum())


def built_cost(ls: LString, born: float, const: dict[str, float], rules: Rules, light: float = 1.0) -> float:
    """Dry mass (g) of the organs born at physiological time ``born`` (the last rewrite): the leaves on the new
    internodes at their full size, blossoms that opened and fruit that set. (The new internodes' wood is the
    pipe model's: paid at the next light reading as the pipes grow, :meth:`Economy.pay_pipes`.)"""
    if len(ls.params) == 0:
        return 0.0
    first = np.where(ls.nparams > 0, ls.params[np.where(ls.nparams > 0, ls.offsets, 0)], np.nan)
    new = first == born
    leaves = int(np.count_nonzero(new & (ls.sym == LEAF)))
    flowers = rules.carbon.blossom_cost * np.count_nonzero(new & (ls.sym == BLOSSOM))
    fruit = rules.carbon.fruit_cost * np.count_nonzero(new & (ls.sym == FRUIT))
    leaf = CLUSTER_AREA * LEAF_ASPECT * const["LS"] ** 2 * AREA * leaf_mass(rules, light)
    return leaves * leaf + float(flowers + fruit)


def root_balance(light: float, supply: float, rules: Rules) -> float:
    """The functional balance's need over supply (Brouwer 1963): the crown's water need, the light its leaves
    catch against the norm (``light``: Simulation.light_growth), over what each root supplies, the stomata's
    opening at the soil's water (``supply``); at most ``root_most``."""
    need = max(light, 0.0)
    return min(need / max(supply, need / rules.carbon.root_most, 1e-9), rules.carbon.root_most)


def root_demand(budget: CarbonBudget, rules: Rules, seconds: float, balance: float) -> float:
    """Sugar (g) the roots want over ``seconds``: their gap to ``root_shoot`` x ``balance`` x the shoot built so
    far, closed over ``root_catch_up``."""
    c = rules.carbon
    target = c.root_shoot * balance * max(budget.built - budget.roots_built, 0.0)
    return max(target - budget.roots_built, 0.0) * min(max(seconds, 0.0) / c.root_catch_up, 1.0)
