"""``python -m archquake.cli``: the command line (:func:`archquake.cli.main`)."""

from . import main

if __name__ == "__main__":
    raise SystemExit(main())
