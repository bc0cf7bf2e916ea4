"""Gait: virtual-subject corpus, step segmentation, step features and the learned StepModel."""

from mjwalk.gait.step import Side, Step

__all__ = ["Side", "Step"]
