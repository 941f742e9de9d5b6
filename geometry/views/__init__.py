"""geometry/views"""
