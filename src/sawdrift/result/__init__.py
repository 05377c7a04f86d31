"""What a run returns: the Result, its evidence and the regime read from it."""

from .regimes import CONTACT_LOST, REGIMES, classify
from .result import SUMMARY_FIELDS, Result

__all__ = ["CONTACT_LOST", "REGIMES", "SUMMARY_FIELDS", "Result", "classify"]
