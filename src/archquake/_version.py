"""The package's version, in a module of its own so that modules can import it without importing
the package root (which would import the whole front door)."""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("archquake")
except PackageNotFoundError:  # running from a source tree
    __version__ = "0.1.0"

__all__ = ["__version__"]
