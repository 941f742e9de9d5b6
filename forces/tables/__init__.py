"""forces/tables"""
