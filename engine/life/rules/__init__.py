"""Layer 4.0, rules: every game rule declared once and read strictly from assets/rules.toml, with named paces."""
