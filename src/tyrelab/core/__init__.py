"""Small compiled building blocks shared by the models and rigs (numba)."""
