"""Analyses built on many runs: scenarios, overturning thresholds and spectra, the utility index
J_OS (Eq. 21), overturning probability over noise realisations and fragility over record suites.
"""
