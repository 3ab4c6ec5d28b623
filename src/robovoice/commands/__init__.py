"""Sub-command groups of the `robovoice` command line (see robovoice.cli)."""
