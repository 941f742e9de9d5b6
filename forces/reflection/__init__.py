"""forces/reflection"""
