"""Arbor's pure core (numpy only: no pygame, no GL), in layers from base up to life.

A layer imports only its own package and lower layers; tests/test_layers.py checks it.
"""
