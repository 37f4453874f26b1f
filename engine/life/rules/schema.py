"""Every game rule declared once: its default, its physical range, its unit and what it means.

The rule dataclasses (rules.py), the validation of assets/rules.toml and of lab and sweep overrides,
the table in docs/rules.md and the units on the sweep figures' axes are all made from this list, so a
rule's default or range is written here and nowhere else. Defaults are the tamagotchi thesis's numbers at the demo
pace; ``scales`` says what a pace does to a rule: ``"time"`` is multiplied by its time scale,
``"rate"`` (per second) divided by it, None left alone (the watering can is held for seconds at any pace).
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Rule:
    """One rule: ``key`` is ``"section.name"``; ``low``..``high`` its physical limits (None for a switch)."""

    key: str
    default: float | bool
    low: float | None
    high: float | None
    unit: str
    meaning: str
    scales: str | None = None
    source: str = ""  # where the value comes from (authors, title), for the rules' table

    @property
    def section(self) -> str:
        """The table of rules.toml the rule lives in."""
        return self.key.partition(".")[0]

    @property
    def name(self) -> str:
        """The rule's key inside its table."""
        return self.key.partition(".")[2]


# section -> (dataclass name, what the section is about), in the order of the Rules dataclass.
SECTION_DOCS = {
    "growth": ("GrowthRules", "When a meter earns growth, and how fast the tree's two clocks run."),
    "sun": ("SunRules", "The sun's orbit (slider defaults and ranges) and how it fills the sun meter."),
    "water": ("WaterRules", "The soil's water as a bucket (the water meter): the roots' uptake, drainage, "
                         "the can, and waterlogging's want of oxygen (engine/life/plant/soil.py)."),
    "health": ("HealthRules", "Neglect, wilting and death."),
    "replant": ("ReplantRules", "The sapling button's meter refill range."),
    "light": ("LightRules", "How light is measured: a shadow grid across the sun's rays (Beer-Lambert)."),
    "wind": ("WindRules", "The wind that sways the tree (it never changes the L-string): strength 0 is still air."),
    "seasons": ("SeasonRules", "A year of seasons counted in days of the sun: spring flush and blossoms, summer "
                               "growth, autumn colours and leaf fall, winter rest."),
    "weather": ("WeatherRules", "Rain showers that fill the water meter (one chance a day, by season) and the wind."),
    "away": ("TimeAwayRules", "What happens while the player is away."),
    "roots": ("RootRules", "Roots: how fast they grow on water and how much they spare it."),
    "carbon": ("CarbonRules", "The carbon budget: sugar fixed by the light each leaf catches, the upkeep of leaves "
                              "and sapwood, what building costs, and starving (engine/life/plant/carbon.py)."),
}

METER = "meter (0..1)"
PHYS = "physiological time"
PER_S = "meter per s"

SCHEMA: tuple[Rule, ...] = (
    Rule("growth.threshold", 0.5, 0.01, 0.99, METER, "a meter counts as full enough above this"),
    Rule("growth.hold_time", 20.0, 0.0, 1e7, "s", "time above the threshold needed to earn growth", "time"),
    Rule("growth.deadline", 40.0, 0.0, 1e7, "s", "a growth cycle longer than this grows less ...", "time"),
    Rule("growth.penalty_time", 40.0, 1e-3, 1e7, "s", "... by exp(-(cycle - deadline) / penalty_time)", "time"),
    Rule("growth.length_rate", 0.06, 0.0, 100.0, f"{PHYS} per s",
         "length clock at the light daylight_full (new internodes)", "rate"),
    Rule("growth.daylight_memory", 125.66667, 1.0, 1e7, "s", "how long the tree remembers the light its leaves "
         "fixed sugar with: its length clock runs on that memory (so through the night too)", "time"),
    Rule("growth.daylight_full", 0.35, 0.01, 1.0, "share of a fully lit leaf's sugar",
         "remembered light at which the length clock runs at length_rate (it runs in proportion to it) ..."),
    Rule("growth.daylight_most", 2.0, 1.0, 10.0, "x length_rate", "... up to this much faster in more light"),
    Rule("growth.girth_rate", 0.1, 0.0, 100.0, "girth time per s", "girth clock at full water growth (thickening)",
         "rate"),
    Rule("growth.rewrite_step", 1.0, 0.01, 100.0, PHYS, "time between two L-system rewrites"),
    Rule("growth.sapling_age", 12.0, 0.0, 1000.0, PHYS, "age of a newly planted sapling (a few internodes)"),
    Rule("growth.apical_fade", 4.0, 0.1, 1000.0, "m of height", "apical control weakens with age: a tree this tall "
         "has half its sapling's (its .lsys BHL's lead over 0.5, the Borchert-Honda lambda at which each shoot's "
         "vigour is its own light), and less the taller it grows (a species' .lsys may set BHF)",
         source="Brown, McAlpine & Kormanik 1967, Apical dominance and form in woody plants: a reappraisal; "
         "Wilson 2000, Apical control of branch growth and angle in woody plants"),
    Rule("growth.dead_linger", 20.0, 0.0, 1e4, PHYS, "a branch that died in deep shade (its .lsys SHED) stands bare "
         "on the tree this much more of its shade time (counted while the crown is in leaf, so through a winter) "
         "before it falls, leaving a stub",
         source="Mäkinen 1999, Growth, suppression, death, and self-pruning of branches of Scots pine in southern "
         "and central Finland (dead branches stay on the stem for years before they fall)"),
    Rule("sun.orbit_height", 0.35, -1.0, 1.0, "orbit radii", "slider: height of the orbit's centre (-1 always night, "
         "1 always day)"),
    Rule("sun.orbit_height_min", -1.0, -1.0, 1.0, "orbit radii", "the orbit height slider's lowest setting"),
    Rule("sun.orbit_height_max", 1.0, -1.0, 1.0, "orbit radii", "the orbit height slider's highest setting"),
    Rule("sun.speed", 0.05, 1e-7, 10.0, "rad per s", "slider: the sun's angular speed (one day ~ 126 s)", "rate"),
    Rule("sun.speed_min", 0.005, 1e-7, 10.0, "rad per s", "the sun speed slider's lowest setting", "rate"),
    Rule("sun.speed_max", 0.5, 1e-7, 10.0, "rad per s", "the sun speed slider's highest setting", "rate"),
    Rule("sun.fill_rate", 0.04, 0.0, 100.0, PER_S, "sun meter filled with the sun at the zenith", "rate"),
    Rule("sun.drain_rate", 0.006, 0.0, 100.0, PER_S, "sun meter drained while the sun is down", "rate"),
    Rule("sun.side", 0.45, -10.0, 10.0, "orbit radii", "how far to one side (+z, south) the sun's path lies"),
    Rule("water.drain_rate", 0.004, 0.0, 100.0, PER_S, "water meter taken up by the roots (and lost from the "
         "soil), always, with the stomata open: as they close in a drying soil the uptake slows with them", "rate"),
    Rule("water.sun_drain_rate", 0.008, 0.0, 100.0, PER_S, "... and taken up extra at full sunshine", "rate"),
    Rule("water.fill_rate", 0.12, 0.0, 100.0, PER_S, "water meter filled while the can is held (any pace)"),
    Rule("water.drown_level", 0.95, 0.0, 1.0, METER, "above this the soil is waterlogged: the oxygen in its pores "
         "runs out (oxygen_time) and the roots take a dose of want of oxygen"),
    Rule("water.drown_time", 30.0, 0.0, 1e7, "s", "the roots' oxygen dose (s of full anoxia) that halves their "
         "uptake, x the species' flood tolerance; past it the tree wilts (by the declared time scale a "
         "flood-intolerant seedling then lives 1-4 weeks in waterlogged soil)", "time",
         source="Kozlowski 1997, Responses of woody plants to flooding and salinity"),
    Rule("water.repair_time", 30.0, 0.1, 1e7, "s", "roots with air heal an oxygen dose over about this long",
         "time", source="chosen: about three real days by the declared time scale (Kozlowski 1997: roots "
         "regrow within days to weeks after a short flood)"),
    Rule("water.oxygen_time", 10.0, 0.01, 1e7, "s", "a waterlogged soil's oxygen is used up over about this long, "
         "and comes back as fast once it drains", "time",
         source="Ponnamperuma 1972, The chemistry of submerged soils (oxygen gone within about a day: 10 s is "
         "a real day by the declared time scale)"),
    Rule("water.field_capacity", 0.8, 0.05, 1.0, METER, "the soil holds water up to this against gravity; more "
         "drains away below the roots", source="Veihmeyer & Hendrickson 1931, The moisture equivalent as a "
         "measure of the field capacity of soils"),
    Rule("water.drainage", 0.07, 0.0, 100.0, "per s", "share of the water above field_capacity that drains "
         "away each second (a wetted soil is back at field capacity within about a real day or two)", "rate",
         source="Allen, Pereira, Raes & Smith 1998, Crop evapotranspiration (FAO-56), ch. 8"),
    Rule("water.leaf_min", 0.45, 0.0, 1.0, "share (0..1)", "leaf vigour (size, how long leaves stay) with an empty "
         "water meter"),
    Rule("water.drought_level", 0.35, 0.0, 1.0, METER, "below this shaded branches die up to 3x faster (drought)"),
    Rule("health.neglect_level", 0.15, 0.0, 1.0, METER, "a meter below this counts as neglect"),
    Rule("health.wilt_rate", 0.02, 0.0, 100.0, "wilt per s", "wilt while neglected or drowning (1 = fully wilted)",
         "rate"),
    Rule("health.recover_rate", 0.01, 0.0, 100.0, "wilt per s", "wilt recovered otherwise", "rate"),
    Rule("health.death_time", 120.0, 0.0, 1e8, "s", "time at full wilt before the tree dies", "time"),
    Rule("health.wilt_shown", 0.5, 0.0, 1.0, "wilt (0..1)", "above this wilt the HUD says the tree is wilting (or "
         "starving, or recovering)"),
    Rule("health.guard_margin", 0.1, 0.0, 0.5, METER, "fast-forward drops to 1x when a meter falls to this above "
         "its need line (water: the growth threshold; sun: the neglect level) or a tree starts to wilt"),
    Rule("health.comfort", 0.8, 0.0, 1.0, METER, "tending (go on after a stop, the kiosk's autopilot) waters a tree "
         "up to this"),
    Rule("replant.meter_min", 0.7, 0.0, 1.0, METER, "a new sapling starts with both meters at least this "
         "(comfortable: well above half)"),
    Rule("replant.meter_max", 0.9, 0.0, 1.0, METER, "... and at most this (below drowning)"),
    Rule("light.cell", 0.9, 0.05, 100.0, "scene units", "side of a shadow cell across the sun's rays (about a leaf)"),
    Rule("light.extinction", 0.55, 0.0, 100.0, "per leaf area per cell area", "Beer-Lambert coefficient"),
    Rule("light.sky", 0.3, 0.0, 1.0, "share (0..1)", "share of the light from the open sky rather than the sun disc"),
    Rule("light.interval", 6.0, 0.01, 1e6, "s", "time between two light measurements", "time"),
    Rule("light.memory", 12.0, 0.01, 1e6, PHYS, "time over which buds and leaves remember their light"),
    Rule("wind.strength", 0.35, 0.0, 5.0, "tree height x 0.1", "sway at the outermost twigs"),
    Rule("wind.direction", 60.0, -360.0, 360.0, "degrees", "from +x toward +z, where the wind blows to"),
    Rule("wind.gusts", 0.5, 0.0, 1.0, "share (0..1)", "how much the strength rises and falls (0 steady, 1 calm to "
         "twice)"),
    Rule("seasons.enabled", True, None, None, "true/false", "false: an endless summer (to study light or water alone)"),
    Rule("seasons.year_days", 28.0, 1.0, 1000.0, "days of the sun", "a year (a season is a quarter of it)"),
    Rule("seasons.start", 0.05, 0.0, 1.0, "share of a year", "where a new garden starts (0 = first day of spring)"),
    Rule("seasons.sun_swing", 0.25, 0.0, 1.0, "orbit radii", "the sun stands this much higher in summer, lower in "
         "winter"),
    Rule("seasons.spring_growth", 1.2, 0.0, 10.0, "x", "growth clocks times this in spring"),
    Rule("seasons.summer_growth", 1.0, 0.0, 10.0, "x", "growth clocks times this in summer"),
    Rule("seasons.autumn_growth", 0.5, 0.0, 10.0, "x", "growth clocks times this in autumn"),
    Rule("seasons.winter_growth", 0.0, 0.0, 10.0, "x", "growth clocks times this in winter (0: winter rest)"),
    Rule("seasons.winter_water", 0.3, 0.0, 10.0, "x", "the water meter drains this much as fast in winter"),
    Rule("seasons.flush", 3.0, 0.0, 100.0, "x", "buds wake this many times as eagerly in spring"),
    Rule("seasons.leaf_fall", 0.08, 0.0, 100.0, f"per {PHYS}", "chance in autumn that a leaf starts to fall"),
    Rule("seasons.leaf_drop", 0.5, 0.0, 1.0, "share of winter", "the leaves still on at winter's start fall within "
         "this first share of it (looked at once a day)"),
    Rule("seasons.mature_age", 80.0, 0.0, 1e6, PHYS, "age from which a healthy tree blossoms in spring"),
    Rule("seasons.bloom_share", 0.6, 0.0, 1.0, "share of spring", "a mature tree may blossom in this first share of "
         "spring ..."),
    Rule("seasons.bloom_health", 0.5, 0.0, 1.0, "share (0..1)", "... while its health (growth earned by both meters, "
         "times 1 - wilt) is above this"),
    Rule("weather.spring_rain", 0.5, 0.0, 1.0, "chance a day", "a rain shower on a spring day"),
    Rule("weather.summer_rain", 0.3, 0.0, 1.0, "chance a day", "a rain shower on a summer day"),
    Rule("weather.autumn_rain", 0.45, 0.0, 1.0, "chance a day", "a rain shower on an autumn day"),
    Rule("weather.winter_rain", 0.2, 0.0, 1.0, "chance a day", "a rain shower on a winter day"),
    Rule("weather.shower", 0.08, 0.0, 1.0, "share of a day", "how long a shower lasts"),
    Rule("weather.rain_fill", 0.02, 0.0, 100.0, PER_S, "water meter filled while it rains", "rate"),
    Rule("weather.rain_wind", 2.0, 0.0, 10.0, "x", "the wind blows this much harder during a shower"),
    Rule("away.cap_days", 14.0, 0.0, 3650.0, "real days", "absence that the garden lives at most"),
    Rule("away.fast_light", 4.0, 0.5, 100.0, "readings a day", "light readings while catching up (fewer: it is "
         "quick)"),
    Rule("roots.growth_rate", 0.06, 0.0, 100.0, "root time per s", "root growth with a full water meter", "rate"),
    Rule("roots.dry_level", 0.2, 0.0, 1.0, METER, "no roots grow with the water meter at or below this ..."),
    Rule("roots.wet_level", 0.8, 0.0, 1.0, METER, "... and they grow at full speed from this level up to "
         "water.drown_level"),
    Rule("roots.step", 0.5, 0.01, 100.0, "root time", "time between two rewrites of the roots' L-string"),
    Rule("roots.drain_relief", 0.35, 0.0, 0.9, "share (0..1)", "a full root system drains the water meter this much "
         "more slowly"),
    Rule("roots.full_length", 150.0, 1.0, 1e5, "scene units", "roots that count as a full root system"),
    Rule("carbon.wood_respiration", 200.0, 0.0, 1e6, "g per m³ of sapwood per s", "upkeep of the living wood "
         "(the pipe model's conducting cross-section times its length)", "rate"),
    Rule("carbon.dormant", 0.05, 0.0, 1.0, "share (0..1)", "upkeep in winter rest, as a share of summer's"),
    Rule("carbon.leaf_mass", 50.0, 1.0, 1000.0, "g per m² of leaf", "what a new leaf costs (leaf mass per area)"),
    Rule("carbon.wood_density", 5e5, 1e4, 1.5e6, "g per m³", "what new wood costs (a species' .lsys may set WD)"),
    Rule("carbon.reserve_time", 1260.0, 1.0, 1e8, "s", "the pool holds at most this long of summer upkeep (ten days "
         "of the sun)", "time"),
    Rule("carbon.keep_time", 126.0, 0.0, 1e8, "s", "this long of upkeep is kept in the pool for nights and winter, "
         "never spent on growth", "time"),
    Rule("carbon.winter_keep", 252.0, 0.0, 1e8, "s", "in autumn and winter (and half of it in spring) this much "
         "more upkeep is kept from growth: the stores a tree lays down for its winter and for the spring before its "
         "new leaves pay", "time", source="Chapin, Schulze & Mooney 1990, The ecology and economics of storage in "
         "plants"),
    Rule("carbon.seed_reserve", 8.0, 0.0, 1e6, "g", "a new sapling's reserve (in its seed and roots)"),
    Rule("carbon.starve_time", 40.0, 0.0, 1e8, "s", "upkeep unpaid (or no leaf at all in a leafy season) for this "
         "long wilts the tree", "time"),
    Rule("carbon.blossom_cost", 0.3, 0.0, 1000.0, "g", "what a blossom costs when it opens (blossoms open, and fruit "
         "sets, only as far as the pool pays for the shoots: extern C)"),
    Rule("carbon.fruit_cost", 4.0, 0.0, 1000.0, "g", "what a fruit costs when it sets (about five leaf clusters)"),
    # The sun from solar geometry through a clear sky (engine/life/plant/solar.py); issue 43.
    Rule("sun.solar_constant", 1361.0, 1300.0, 1420.0, "W/m²", "the sun's irradiance at the top of the "
         "atmosphere at the mean Earth-Sun distance", source="Kopp & Lean 2011, A new, lower value of total solar "
         "irradiance"),
    Rule("sun.transmittance", 0.7, 0.3, 0.95, "share (0..1)", "clear-sky beam transmittance: the beam reaching the "
         "ground is solar_constant x transmittance^(air mass^transmittance_power) (air mass by Kasten & Young 1989)",
         source="Meinel & Meinel 1976, Applied Solar Energy"),
    Rule("sun.transmittance_power", 0.678, 0.3, 1.5, "exponent", "... the power of the air mass in it",
         source="Meinel & Meinel 1976, Applied Solar Energy"),
    Rule("sun.diffuse", 0.1, 0.0, 1.0, "share of the beam", "diffuse light from a clear sky on the horizontal, as "
         "a share of the direct beam there", source="Meinel & Meinel 1976 (the ten per cent rule of thumb)"),
    Rule("sun.par_share", 0.48, 0.4, 0.55, "share (0..1)", "share of the global irradiance that is "
         "photosynthetically active (PAR, 400-700 nm)", source="McCree 1972, Test of current definitions of "
         "photosynthetically active radiation against leaf photosynthesis data (0.45-0.50)"),
    Rule("sun.par_photons", 4.57, 4.0, 5.0, "µmol per J", "photons per joule of sunlight's PAR",
         source="McCree 1972, as above"),
    Rule("sun.shade", 0.0, 0.0, 0.99, "share (0..1)", "share of the sun's light removed above the tree (a shade "
         "cloth or a canopy): it dims the sun, the day stays as long"),
    Rule("seasons.real_year", 365.0, 1.0, 3650.0, "real days", "the declared time scale: a game year (year_days "
         "game days) stands for this span of a real tree's life, so a game day stands for real_year / year_days "
         "real days of its growing year (13 at the defaults, at every pace: the pace sets only how long a game day "
         "lasts to the player); rates are reported in real units over this scale"),
    # A leaf's light response and dark respiration (engine/life/plant/photosynthesis.py); issue 43.
    Rule("carbon.amax", 12.0, 1.0, 60.0, "µmol CO2 per m² of leaf per s", "light-saturated gross assimilation of "
         "a leaf (a species' .lsys AMAX replaces it)", source="Wullschleger 1993, Biochemical limitations to carbon "
         "assimilation in C3 plants (broadleaf trees 5-25)"),
    Rule("carbon.quantum_efficiency", 0.05, 0.01, 0.125, "mol CO2 per mol of photons", "a leaf's quantum "
         "efficiency: the light response's slope in dim light (a species' .lsys QE replaces it)",
         source="Ehleringer & Björkman 1977, Quantum yields for CO2 uptake in C3 and C4 plants (0.05 at 30 °C)"),
    Rule("carbon.curvature", 0.7, 0.0, 0.99, "0..1", "curvature theta of the non-rectangular hyperbola (0: a "
         "rectangular hyperbola, 1: a sharp corner at Amax)", source="Thornley 1976, Mathematical Models in Plant "
         "Physiology; Ögren & Evans 1993 (0.7-0.9)"),
    Rule("carbon.dark_share", 0.07, 0.01, 0.3, "share of Amax", "a leaf's dark respiration, as a share of its Amax "
         "(a species' .lsys RDS replaces it)", source="Reich et al. 1998, Relationships of leaf dark respiration to "
         "leaf nitrogen, specific leaf area and leaf life-span (about 0.05-0.1)"),
    Rule("water.stomata_scale", 0.25, 0.01, 1.0, METER, "the stomata close smoothly as the water meter falls, "
         "open (1 - exp(-meter / this)) / (1 - exp(-1 / this)): at a meter of this much 64 %, at half of it 40 %; the "
         "roots take up water as they let it go (engine/life/plant/soil.py)",
         source="the exponential soil-water response of Jarvis 1976, The interpretation of the variations in leaf "
         "water potential and stomatal conductance found in canopies in the field"),
    # Allocation to roots by a functional balance (carbon.root_demand); issue 43.
    Rule("carbon.root_shoot", 0.35, 0.05, 2.0, "g of root per g of shoot", "the root:shoot the functional balance "
         "aims at with the crown's light at the norm (daylight_full) and a moist soil: more light (the crown's water "
         "need) raises it, a drier soil (less supply per root) raises it, shade lowers it",
         source="Brouwer 1963, Functional equilibrium; Poorter et al. 2012, Biomass allocation to leaves, stems and "
         "roots: meta-analyses of interspecific variation and environmental control (young trees 0.2-0.5)"),
    Rule("carbon.growth_cost", 1.4, 1.1, 2.0, "g of sugar per g of dry mass", "what building costs: the sugar "
         "built into a gram of leaf, wood or root and the growth respiration that builds it (the pool pays this "
         "much for every gram built)", source="Penning de Vries, Brunsting & van Laar 1974, Products, requirements "
         "and efficiency of biosynthesis: a quantitative approach (1.2-1.5 g glucose per g for leaves and wood)"),
    Rule("carbon.growth_fill", 0.5, 0.05, 1.0, "share of the pool's capacity", "the pool's fill at which the "
         "tree builds at its clock's pace (extern C = 1): in proportion to the fill below it, so growth is set by "
         "the sugar the leaves earn", source="growth driven by the reserve's substrate (Thornley 1972, A balanced "
         "quantitative model for root:shoot ratios in vegetative plants)"),
    Rule("carbon.growth_most", 2.0, 1.0, 10.0, "x the clock's pace", "a pool fuller than growth_fill builds up to "
         "this much faster than the clock's pace (a full pool builds more)"),
    Rule("carbon.root_respiration", 3.0, 1.0, 40.0, "nmol CO2 per g of root per s", "the roots' upkeep (a real "
         "rate, made the game's by the declared time scale)", source="Reich et al. 2008, Scaling of respiration to "
         "nitrogen in leaves, stems and roots of higher land plants (fine roots about 5-20 at 20-25 °C; the "
         "coarser roots that make most of a young tree's root mass respire far less)"),
    Rule("carbon.fine_root_leaf", 1.0, 0.1, 5.0, "g of fine root per g of leaf", "the fine roots a tree keeps for "
         "its leaves (they respire at root_respiration; the rest of its roots is coarse)",
         source="Vanninen & Mäkelä 1999, Fine root biomass of Scots pine stands differing in age and soil fertility "
         "in southern Finland (fine root to foliage mass about 0.3-1, steady with age)"),
    Rule("carbon.coarse_root_share", 0.1, 0.0, 1.0, "share of root_respiration", "a coarse root's upkeep per g "
         "against a fine root's (a tree's roots grow with its wood; most of an old tree's are coarse)",
         source="Desrochers, Landhäusser & Lieffers 2002, Coarse and fine root respiration in aspen (Populus "
         "tremuloides) (coarse roots respire far less per g than fine roots)"),
    Rule("carbon.shade_lma", 0.5, 0.2, 1.0, "share of a sun leaf's", "a leaf grown in deep shade has this share of "
         "a sun leaf's mass per area (leaf_mass), a leaf in sun_leaf_light or more the whole of it, in proportion "
         "between: shade leaves are thinner, their specific leaf area higher",
         source="Poorter et al. 2009, Causes and consequences of variation in leaf mass per area (LMA): a meta-"
         "analysis (LMA about halves from high light to deep shade)"),
    Rule("carbon.sun_leaf_light", 0.5, 0.05, 1.0, "share of the open sky's light", "leaves that get this share of "
         "the open sky's light or more grow as sun leaves (their mass per area saturates in bright light)",
         source="Poorter et al. 2009, as above"),
    Rule("carbon.root_most", 4.0, 1.0, 20.0, "x root_shoot", "the balance's need over supply at most (a dry soil's)"),
    Rule("carbon.root_catch_up", 125.66667, 1.0, 1e7, "s", "the roots close their gap to the balance's target over "
         "about this long (a day of the sun), as far as the pool pays", "time"),
    Rule("water.flood_tolerance", 1.0, 0.1, 20.0, "x", "how much longer a tree's roots bear waterlogged soil before "
         "it wilts, and how much more slowly it then wilts (a species' .lsys FLOOD replaces it)",
         source="Kozlowski 1997, Responses of woody plants to flooding and salinity (intolerant seedlings die in 1-4 "
         "weeks, tolerant ones live months)"),
)


def find_rule(key: str, schema: tuple[Rule, ...] = SCHEMA) -> Rule | None:
    """The rule a ``"section.name"`` key names, or None."""
    return next((r for r in schema if r.key == key), None)


def rules_table_markdown(schema: tuple[Rule, ...] = SCHEMA) -> str:
    """docs/rules.md's table of every rule: one row per rule, a heading per section of rules.toml."""
    lines = []
    for section, (_, doc) in SECTION_DOCS.items():
        lines += [f"### [{section}]", "", doc, "", "| rule | default | range | unit | meaning | pace |",
                  "|---|---|---|---|---|---|"]
        for r in (r for r in schema if r.section == section):
            span = "" if r.low is None else f"{r.low:g} .. {r.high:g}"
            default = str(r.default).lower() if isinstance(r.default, bool) else f"{r.default:g}"
            cited = f" (source: {r.source})" if r.source else ""
            pace = {"time": "x time_scale", "rate": "/ time_scale"}.get(r.scales or "", "")
            lines.append(f"| `{r.name}` | {default} | {span} | {r.unit} | {r.meaning}{cited} | {pace} |")
        lines.append("")
    return "\n".join(lines)


TABLE_MARKERS = ("<!-- rules-table -->\n", "<!-- /rules-table -->\n")  # its place in docs/rules.md
