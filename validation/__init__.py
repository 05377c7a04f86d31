"""The validation cases, one fact per file (docs/validation.md).

This folder is shipped inside the sawdrift package as ``sawdrift.validation.cases`` (pyproject maps
it), so ``sawdrift validate`` finds the cases from an installed wheel as well as from a checkout.
Files starting with ``_`` (like this one) are not cases.
"""
