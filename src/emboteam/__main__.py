"""``python -m emboteam``: the same command line as the ``emboteam`` script, for
environments where the script is not on PATH."""

from emboteam.entry import main

if __name__ == "__main__":
    main()
