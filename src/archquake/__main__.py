"""``python -m archquake``: the command line (:func:`archquake.cli.main`)."""

if __name__ == "__main__":
    from .cli import main

    raise SystemExit(main())
