"""File formats: OBJ, TopMod's .dlfl, STL and PLY (placeholder until the io work lands)."""
