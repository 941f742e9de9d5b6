"""forces/radiation"""
