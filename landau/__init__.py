"""landau"""
