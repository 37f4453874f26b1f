"""How a crown grows into its lobes and the leaves it carries (issue 48's parameter panel): a
:class:`CrownStyle`, its options (default, range, step, unit and meaning each) and presets, read from
``assets/crowns.toml`` strictly (a wrong name, type or value is one line with the file, line and column)."""

from __future__ import annotations

from dataclasses import dataclass, fields, replace
from pathlib import Path

from arbor.engine.base.assets import assets_dir
from arbor.engine.base.errors import SettingsError
from arbor.engine.base.reader import read_user_toml

STYLE_FILE = "crowns.toml"
OPTION_KEYS = {"default", "min", "max", "step", "unit", "meaning"}


@dataclass(frozen=True)
class CrownStyle:
    """A crown's growth (Zhang et al. section 5) and leaves; the meanings are in assets/crowns.toml."""

    twig: float = 0.2  # the longest piece, of a lobe's size
    fork: float = 40.0  # degrees: a node's attractors within this angle grow one branch
    straight: float = 0.8  # alpha: the weight of a branch's own heading
    rise: float = 0.3  # -beta: the pull up against gravity (negative: down)
    leaf_size: float = 1.0  # times the species' leaf length
    leaves: float = 1.0  # leaves per branch tip
    reach: float | None = None  # attractors this close (of a lobe's size) are used up; None: half a twig

    def tip(self, birth: str) -> str:
        """The modules ending every crown branch: ``leaves`` leaves born at ``birth``, rolled apart."""
        count = max(1, round(self.leaves))
        return f"[&(45)L({birth})]" + "".join(f"[/({360 * k // count})&(45)L({birth})]" for k in range(1, count))


DEFAULT_STYLE = CrownStyle()


@dataclass(frozen=True)
class Option:
    """One option of the panel."""

    name: str
    default: float
    low: float
    high: float
    step: float
    unit: str
    meaning: str


def load_styles(path: str | Path | None = None) -> tuple[dict[str, Option], dict[str, CrownStyle]]:
    """The options and the presets (as styles) of ``path`` (default: the assets' crowns.toml)."""
    path = Path(path) if path is not None else assets_dir() / STYLE_FILE
    _, data = read_user_toml(path, SettingsError)
    known = {f.name for f in fields(CrownStyle)} - {"reach"}
    options = {}
    for name, spec in _table(data, "options", path).items():
        where = f"{path}: [options.{name}]"
        if name not in known or not isinstance(spec, dict) or set(spec) != OPTION_KEYS:
            raise SettingsError(f"[options.{name}] must be one of {sorted(known)} with {sorted(OPTION_KEYS)}",
                                str(path))
        values = [spec[k] for k in ("default", "min", "max", "step")]
        if not all(isinstance(v, int | float) and not isinstance(v, bool) for v in values):
            raise SettingsError(f"{where}: default, min, max and step must be numbers", str(path))
        low, high = float(spec["min"]), float(spec["max"])
        if not (low <= float(spec["default"]) <= high and float(spec["step"]) > 0):
            raise SettingsError(f"{where}: need min <= default <= max and a step above 0", str(path))
        options[name] = Option(name, float(spec["default"]), low, high, float(spec["step"]), str(spec["unit"]),
                               str(spec["meaning"]))
    base = CrownStyle(**{name: option.default for name, option in options.items()})
    presets = {}
    for name, values in _table(data, "presets", path).items():
        if not isinstance(values, dict) or not set(values) <= set(options):
            raise SettingsError(f"[presets.{name}] may set only {sorted(options)}", str(path))
        for key, value in values.items():
            option = options[key]
            if isinstance(value, bool) or not isinstance(value, int | float) or not option.low <= value <= option.high:
                raise SettingsError(f"[presets.{name}] {key} = {value!r}: a number within {option.low:g}.."
                                    f"{option.high:g}", str(path))
        presets[name] = replace(base, **{key: float(value) for key, value in values.items()})
    return options, presets


def _table(data: dict, name: str, path: Path) -> dict:
    table = data.get(name, {})
    if not isinstance(table, dict):
        raise SettingsError(f"[{name}] must be a table", str(path))
    return table


def stepped(style: CrownStyle, option: Option, steps: int) -> CrownStyle:
    """``style`` with ``option`` moved ``steps`` steps, kept within its range."""
    value = getattr(style, option.name) + steps * option.step
    return replace(style, **{option.name: round(min(max(value, option.low), option.high), 6)})
