"""Example third-party sawdrift plugin: the ``hertz_tsuji`` contact model."""

from .hertz_tsuji import HertzTsuji, HertzTsujiParams

__all__ = ["HertzTsuji", "HertzTsujiParams"]
