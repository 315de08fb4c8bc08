"""``python -m crossval``: the command line."""

from .cli import main

main(prog_name="crossval")
