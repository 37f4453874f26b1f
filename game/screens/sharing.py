"""Settings -> Share and Garden -> Import: trees shared as postcards in the saves folder's ``cards/``.

Share writes a postcard PNG of the cared-for tree there (game/render/postcard.py: the picture, with the
tree's save inside); Import plants the newest card there whose tree the garden does not hold yet, after
the same checks as any shared save (engine/life/keep/card.py). A card a friend sent is dropped into that
folder; the message says where it is."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from arbor.engine.base.files import atomic_write
from arbor.engine.life.keep.card import plant_card, read_card
from arbor.engine.life.keep.save_check import SaveError
from arbor.engine.life.rules.rules import Rules
from arbor.engine.life.world.actions import Action
from arbor.game.screens.state import GameState
from arbor.game.strings import text

MAX_CARDS_LOOKED_AT = 50  # newest cards tried by one Import press (each is read and checked)


class Sharing:
    """The two sharing buttons: their handlers join the care actions' (see :meth:`handlers`)."""

    def __init__(self, state: GameState, saves: Path, rules: Rules, lsystem_name: str, ctx=None) -> None:
        self.state, self.rules, self.lsystem_name, self.ctx = state, rules, lsystem_name, ctx
        self.folder = saves / "cards"

    def handlers(self) -> dict[Action, Callable[[float], None]]:
        """Share and Import act when pressed (value 1), not when let go."""
        return {Action.SHARE: lambda v: self.share() if v else None,
                Action.IMPORT: lambda v: self.import_card() if v else None}

    def share(self) -> Path | None:
        """Write the cared-for tree's postcard into the cards folder; the path, or None when it failed."""
        from arbor.game.render.postcard import card_file

        world, garden = self.state.world, self.state.garden
        path = self.folder / f"{world.lineage.species}-{world.lineage.id[:8]}.png"
        try:
            self.folder.mkdir(parents=True, exist_ok=True)
            atomic_write(path, card_file(world, garden.family, self.lsystem_name, self.ctx))
        except OSError as err:
            self.state.say(text("messages.share_failed", reason=err.strerror or str(err)), 8)
            return None
        self.state.say(text("messages.shared", path=str(path)), 8)
        return path

    def import_card(self) -> bool:
        """Plant the newest card's tree that the garden does not hold; True when one was planted."""
        state = self.state
        cards = sorted(self.folder.glob("*.png"), key=_mtime, reverse=True)[:MAX_CARDS_LOOKED_AT]
        known = {w.lineage.id for w in state.garden.worlds}
        refused = 0
        for card in cards:
            try:
                shared = read_card(card, self.rules)
            except SaveError:
                refused += 1
                continue
            if shared.world.lineage.id in known:
                continue
            try:
                plant_card(state.garden, shared)
            except ValueError as why:
                state.say(str(why), 6)
                return False
            state.remember()
            state.say(text("messages.imported", name=card.name, count=len(state.garden.worlds)), 6)
            return True
        state.say(text("messages.no_cards", folder=str(self.folder), refused=refused), 10)
        return False


def _mtime(path: Path) -> float:
    """When a card arrived (0 when it cannot be asked: it is tried last)."""
    try:
        return path.stat().st_mtime
    except OSError:
        return 0.0
