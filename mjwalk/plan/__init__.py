"""mjwalk.plan"""
