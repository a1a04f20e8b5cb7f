"""Tests of pipeline/store: where results live, how their keys are derived."""
