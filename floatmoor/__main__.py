"""``python -m floatmoor`` runs the command line."""

from floatmoor.cli import run

run()
