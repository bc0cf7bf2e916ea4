"""mjwalk.world"""
