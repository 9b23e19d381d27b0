"""``python -m floatmoor.cli`` runs the command line (as ``python -m floatmoor``)."""

from floatmoor.cli import run

run()
