"""Readers of hydrodynamic data written by other codes (Capytaine, WAMIT, BEMIO/WEC-Sim)."""
