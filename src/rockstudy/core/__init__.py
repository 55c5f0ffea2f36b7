"""The foundation every layer stands on: physical and numerical constants, input validation with
messages that name the user's key, numba inlining rules, and atomic file I/O.
"""
