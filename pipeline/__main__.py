"""Allow ``python -m pipeline`` as an alias of the ``rockscreen`` command."""

from pipeline.cli import main

main(prog_name="rockscreen")
