"""Python helpers shared by BioVision's Python nodes (reports, mission director, teacher)."""
