"""Postcards: a tree shared as a PNG picture that carries its save inside, in a compressed iTXt text chunk.

Any image viewer shows the picture; `arbor import` (or Garden -> Import) reads the save back out and
checks it like any shared save. The PNG chunks are walked here with ``struct`` and ``zlib`` rather than an
image library: the engine stays numpy-only, and every size is bounded by us before anything is inflated
(a card is hostile input: a chunk may lie about its length, its text may be a zlib bomb).
"""

from __future__ import annotations

import struct
import zlib
from pathlib import Path

from arbor.engine.base.reader import read_user_bytes
from arbor.engine.life.keep.save import MAX_BYTES, SavedGarden, garden_text, read_garden_bytes
from arbor.engine.life.keep.save_check import SaveError
from arbor.engine.life.plant.sim import Rules
from arbor.engine.life.world.garden import MAX_GARDEN, Garden
from arbor.engine.life.world.world import World

SIGNATURE = b"\x89PNG\r\n\x1a\n"
KEYWORD = b"Arbor save"  # the iTXt chunk's keyword (PNG keywords are 1-79 Latin-1 characters)
MAX_CARD_BYTES = 96 * 1024 * 1024  # a card file: the picture plus a compressed save
MAX_CHUNKS = 100_000  # chunks walked at most (a real card has a handful; IDAT may be split in many)


def card_bytes(png: bytes, saved: SavedGarden) -> bytes:
    """The PNG ``png`` with ``saved``'s save text in a compressed iTXt chunk right after the header (before
    the picture data, where tools that keep metadata look for it)."""
    chunks = list(_chunks(png, "the picture"))
    if not chunks or chunks[0][0] != b"IHDR":
        raise ValueError("the picture is not a PNG that starts with its header")
    text = garden_text(saved).encode("utf-8")
    data = KEYWORD + b"\x00" + b"\x01\x00" + b"\x00" + b"\x00" + zlib.compress(text, 9)
    header_end = len(SIGNATURE) + 12 + len(chunks[0][1])
    return png[:header_end] + _chunk(b"iTXt", data) + png[header_end:]


def card_save_bytes(path: str | Path) -> bytes:
    """The save text a card at ``path`` carries, as bytes; a SaveError naming the file when it is not a
    PNG, carries no Arbor save, or its save is larger than a save may be."""
    path = Path(path)
    raw = read_user_bytes(path, MAX_CARD_BYTES, CardError)  # (the one reader: a regular file, size bounded)
    chunks = list(_chunks(raw, str(path)))  # every chunk to IEND, each length and CRC checked
    if chunks[0][0] != b"IHDR":
        raise _error("not a PNG picture (it does not start with its header chunk, IHDR)", str(path))
    for kind, data in chunks:
        if kind == b"iTXt" and data.startswith(KEYWORD + b"\x00"):
            return _itxt_text(data[len(KEYWORD) + 1:], str(path))
    raise _error("this picture carries no Arbor save (was it re-saved by a program that drops PNG text "
                    "chunks? share the card file itself)", str(path))


def read_card(path: str | Path, rules: Rules | None = None) -> SavedGarden:
    """The garden a card carries, checked like any shared save (errors name the card)."""
    return read_garden_bytes(card_save_bytes(path), path, rules)


def plant_card(garden: Garden, shared: SavedGarden) -> World:
    """Plant the tree a card carried (``shared``, from :func:`read_card`) beside the others of ``garden``,
    with its ancestry; a ValueError saying why when the garden already holds that tree or is full."""
    world = shared.world
    if any(w.lineage.id == world.lineage.id for w in garden.worlds):
        raise ValueError(f"this tree ({world.lineage.id}) is already in your garden")
    if garden.full:
        raise ValueError(f"your garden is full ({MAX_GARDEN} trees): make room first")
    for member in shared.family.members.values():
        garden.family.add(member)
    return garden.adopt(world)


class CardError(SaveError):
    """A SaveError about a card as a picture: no line and column (it has none; the message names the byte
    where it can)."""

    def __init__(self, message: str, file: str = "<card>", line: int = 0, col: int = 0) -> None:
        super().__init__(message, file, line, col)


def _error(message: str, label: str) -> SaveError:
    """A :class:`CardError` about the card ``label``."""
    return CardError(message, label)


def _chunk(kind: bytes, data: bytes) -> bytes:
    """One PNG chunk: length, type, data, CRC of type and data."""
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def _chunks(raw: bytes, label: str):
    """(type, data) of each chunk of the PNG ``raw``, up to IEND; lengths and CRCs checked."""
    if not raw.startswith(SIGNATURE):
        raise _error("not a PNG picture", label)
    at = len(SIGNATURE)
    for _ in range(MAX_CHUNKS):
        if at + 12 > len(raw):
            raise _error("a PNG cut short (no end chunk)", label)
        (length,), kind = struct.unpack(">I", raw[at:at + 4]), raw[at + 4:at + 8]
        end = at + 12 + length
        if end > len(raw):
            raise _error(f"a PNG chunk longer than the file (byte {at})", label)
        data = raw[at + 8:end - 4]
        if struct.unpack(">I", raw[end - 4:end])[0] != zlib.crc32(kind + data):
            raise _error(f"a damaged PNG chunk {kind.decode('latin-1')!r} (byte {at})", label)
        yield kind, data
        if kind == b"IEND":
            return
        at = end
    raise _error(f"more than {MAX_CHUNKS:,} PNG chunks", label)


def _itxt_text(rest: bytes, label: str) -> bytes:
    """The text of an iTXt chunk's body after its keyword: flag, method, language, translated keyword,
    then the (compressed) text, inflated to at most MAX_BYTES."""
    if len(rest) < 2:
        raise _error("a damaged Arbor save chunk", label)
    compressed, method = rest[0], rest[1]
    parts = rest[2:].split(b"\x00", 2)
    if len(parts) != 3 or compressed not in (0, 1) or method != 0:
        raise _error("a damaged Arbor save chunk", label)
    body = parts[2]
    if not compressed:
        return body
    inflater = zlib.decompressobj()
    try:
        text = inflater.decompress(body, MAX_BYTES + 1)
    except zlib.error:
        raise _error("the Arbor save chunk does not inflate (damaged)", label) from None
    if len(text) > MAX_BYTES or inflater.unconsumed_tail:
        raise _error(f"the save inside is too large (more than {MAX_BYTES:,} bytes)", label)
    return text
