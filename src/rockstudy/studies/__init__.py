"""The study's bookkeeping: the workflow's config turned into library objects and checked, the
labelled datasets and tables the workflow writes, and the reproduction studies (noise readings,
device calibration, the claims checklist).
"""
