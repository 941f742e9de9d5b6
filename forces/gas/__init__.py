"""forces/gas"""
