"""The pipeline's figures: one module per stage, each function takes the stage's
arrays and returns a matplotlib figure (Agg backend, no file I/O); the stage
saves it with ``pipeline.store.atomic.save_figure``."""
