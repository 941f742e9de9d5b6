"""geometry/rays"""
