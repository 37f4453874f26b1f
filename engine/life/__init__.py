"""Layer 4, life: rules, the plant and its form, the world and garden, saves, lineage and the lab, by job."""
