"""Arm motion: trajectory representation, DCS network, reach model, reach generator, hands."""
