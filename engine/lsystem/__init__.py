"""Layer 1, language: expressions, L-strings, the .lsys parser and parallel derivation; imports only engine.base."""
