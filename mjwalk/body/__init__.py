"""mjwalk.body"""
