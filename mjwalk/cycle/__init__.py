"""mjwalk.cycle"""
