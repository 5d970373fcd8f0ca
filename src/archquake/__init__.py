"""archquake: seismic response of masonry arches with geometrical irregularities.

The chain of the paper "Dynamic response of masonry arch with geometrical irregularities
subjected to a pulse-type ground motion": geometry -> limit analysis -> four-link mechanism ->
impacts -> time histories -> failure domains and fragility.
"""

from importlib.metadata import PackageNotFoundError, version

from .geometry import GRAVITY, Arch, circular_arch, irregular_arch
from .reference_arches import oppenheim

try:
    __version__ = version("archquake")
except PackageNotFoundError:  # running from a source tree
    __version__ = "0.1.0"

__all__ = ["GRAVITY", "Arch", "circular_arch", "irregular_arch", "oppenheim", "__version__"]
