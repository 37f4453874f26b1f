"""Arbor's name on the package index and its installed version (the command and the import package are both
`arbor`; the distribution is `arbor-trees` because `arbor` on PyPI is a neuron simulator: README.md says more)."""

from __future__ import annotations

DISTRIBUTION = "arbor-trees"


def version() -> str:
    """The installed distribution's version (what `arbor --version` prints and exports record)."""
    from importlib.metadata import PackageNotFoundError
    from importlib.metadata import version as installed

    try:
        return installed(DISTRIBUTION)
    except PackageNotFoundError:  # run from a checkout that was never installed
        return "unknown (not installed)"
