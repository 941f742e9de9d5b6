"""forces/export"""
