"""Allow ``python -m rockscreen.pipeline`` as an alias of the ``rockscreen`` command."""

from rockscreen.pipeline.cli import main

main(prog_name="rockscreen")
