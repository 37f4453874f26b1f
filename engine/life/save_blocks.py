"""Reading a save's TOML without making TOML walk its L-strings.

A save keeps each L-string in a multi-line literal string (``lstring = '''...'''``). A literal string
holds its text as it is, but the TOML reader still checks it character by character (about 35 ms for
a 100k-module tree). So the blocks are cut out first (the text between the quotes, which needs no
unescaping), each replaced by a marker that keeps its line breaks (error positions stay right), the
rest is read by TOML, and the blocks go back where the markers are. Anything unusual (a marker found
elsewhere, a block TOML would end differently) and the whole text is read by TOML as it is.
"""

from __future__ import annotations

import secrets
import tomllib

_KEYS = ("\nlstring = '''\n", "\nroots = '''\n")  # at a line start, as the writer puts them


def loads(text: str) -> dict:
    """``tomllib.loads(text)``, faster for saves with big L-strings (see module docstring)."""
    lifted, blocks = _lift(text)
    if not blocks:
        return tomllib.loads(text)
    try:
        data = tomllib.loads(lifted)
    except tomllib.TOMLDecodeError:
        return tomllib.loads(text)  # let TOML name the problem in the text as written
    if _put_back(data, blocks) != len(blocks):
        return tomllib.loads(text)
    return data


def _lift(text: str) -> tuple[str, dict[str, str]]:
    nonce = secrets.token_hex(8)
    out, blocks, pos = [], {}, 0
    while True:
        found = [at for at in (text.find(key, pos) for key in _KEYS) if at >= 0]
        if not found:
            break
        body_at = text.index("\n", min(found) + 1) + 1  # after the key's line
        end = text.find("'''", body_at)
        if end < 0 or text.startswith("'", end + 3):
            break  # an unclosed block, or one ending in quotes: TOML decides
        body = text[body_at:end]
        marker = f"@arbor-block-{nonce}-{len(blocks)}@"
        blocks[marker] = body
        out += [text[pos:body_at], marker, "\n" * body.count("\n")]
        pos = end
    out.append(text[pos:])
    return "".join(out), blocks


def _put_back(data, blocks: dict[str, str]) -> int:
    """Replace marker values by their blocks everywhere in ``data``; returns how many were replaced."""
    found = 0
    items = data.items() if isinstance(data, dict) else enumerate(data) if isinstance(data, list) else ()
    for key, value in items:
        if isinstance(value, str) and value.rstrip("\n") in blocks:
            data[key] = blocks[value.rstrip("\n")]
            found += 1
        elif isinstance(value, dict | list):
            found += _put_back(value, blocks)
    return found
