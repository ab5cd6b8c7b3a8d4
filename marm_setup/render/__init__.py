"""Rendering a config package: the per-template context, the whole package in memory, and the atomic writer with its edit-guarding manifest."""
