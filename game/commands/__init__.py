"""Headless subcommands of arbor (lab --out, landscape): they write files and open no window."""
