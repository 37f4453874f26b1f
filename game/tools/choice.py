"""The modeler's tools as one choice: one tool in use at a time (Draw, Crown, Shape, Prune, Symbols), lit on the
tool bar (game/render/ui.py ToolBar), told by the hint line (what a drag does with it), with the option of
the tool in use (Crown's style panel, Shape's lobe operation, Prune's branch edit: cut, width, angle or
length; Symbols' region edit). A tool stays in use until another is chosen; Draw, entering the modeler,
leaving it and a new sapling are back to the draw tool with no overlay left (lobe rings, regions, the
joint marker, a picked branch, the style panel).
"""

from __future__ import annotations

from arbor.engine.modeling.edits import EDIT_SETS
from arbor.game.render.ui import ToolBar
from arbor.game.strings import text

TOOLS = {"draw": None, "crown": "crown", "shape": "shaping", "prune": "pruning", "symbols": "symbols"}  # bar name: flag


class ToolChoice:
    """Mixin of the modeling mode (game/screens/modeler.py): its tool flags (``crown``, ``shaping``,
    ``pruning``, ``symbols``; none set: the draw tool), the tool bar ``bar`` and the region edit ``edit``
    chosen; it uses the mode's ``active``, ``toggle``, ``cancel``, ``crown_tool``, ``prune_tool``,
    ``region_tool`` and ``state``."""

    crown = shaping = pruning = symbols = False
    edit = EDIT_SETS[0]
    bar: ToolBar

    def reset_tools(self) -> None:
        """Back to the draw tool with no overlay: no stroke, region, contours, lobe rings or joint marker."""
        self.crown = self.shaping = self.pruning = self.symbols = False
        self.region_tool.clear()
        self.region_tool.labels = []
        self.crown_tool.clear()
        self.prune_tool.clear()
        self.crown_panel.visible = False
        self.cancel()
        self.show_bar()

    @property
    def current_tool(self) -> str:
        """The tool in use, by its bar name: draw, crown, shape, prune or symbols."""
        return next((name for name, flag in TOOLS.items() if flag and getattr(self, flag)), "draw")

    def tool(self, name: str, quiet: bool = False) -> None:
        """Use tool ``name`` (draw, crown, shaping, pruning or symbols; entering the modeler if needed).
        A tool stays in use until another is chosen: choosing the one in use again keeps it."""
        if not self.active:
            self.toggle()
        self.crown = self.shaping = self.pruning = self.symbols = False
        if name != "draw":
            setattr(self, name, True)
        self.region_tool.clear()
        self.crown_panel.visible = self.crown_panel.visible and name == "crown"
        self.cancel()
        self.show_bar()
        if quiet:
            return
        if name == "shaping":
            self.state.say(text("messages.shaping_on", op=text(f"shapes.{self.crown_tool.op}")))
        else:
            self.state.say(text(f"messages.{name}_on"))

    def show_bar(self) -> None:
        """The tool bar as the tools are now: shown in the modeler, the tool in use lit, its option."""
        tool = self.current_tool
        self.bar.show(self.active, tool, self.option_label() if tool in ("crown", "shape", "prune", "symbols") else "")

    def hint(self) -> str:
        """The hint line in the modeler: what a drag does with the tool in use."""
        tool = self.current_tool
        if tool == "prune" and self.prune_tool.op == "brush":
            return text("hints.modeler_brush")
        if tool == "prune" and self.prune_tool.op != "cut":
            return text("hints.modeler_branch", op=text(f"branch_ops.{self.prune_tool.op}"))
        return text(f"hints.modeler_{tool}", op=text(f"shapes.{self.crown_tool.op}"), edit=text(f"edits.{self.edit}"))

    def option_label(self) -> str:
        """The menu option button's label: the lobe operation with the shape tool, else the region edit."""
        if self.shaping:
            return text("menu.shape_op", op=text(f"shapes.{self.crown_tool.op}"))
        if self.crown:
            return text("menu.crown_style_close" if self.crown_panel.visible else "menu.crown_style")
        if self.pruning:
            return text("menu.branch_op", op=text(f"branch_ops.{self.prune_tool.op}"))
        return text("menu.edit", name=text(f"edits.{self.edit}"))

    def next_option(self) -> str:
        """The menu's option button: the next lobe operation with the shape tool, else the next region
        edit. Returns the button's new label."""
        if self.shaping:
            self.crown_tool.next_op()
        elif self.crown:
            self.crown_panel.visible = not self.crown_panel.visible
        elif self.pruning:
            self.prune_tool.next_op()
            self.state.say(self.hint())
        else:
            self.edit = EDIT_SETS[(EDIT_SETS.index(self.edit) + 1) % len(EDIT_SETS)]
        self.show_bar()
        return self.option_label()
