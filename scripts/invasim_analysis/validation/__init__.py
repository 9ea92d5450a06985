"""The validation campaign's analysis (scripts/validation.py, docs/validation.md)."""
