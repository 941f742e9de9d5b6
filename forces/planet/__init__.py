"""The planet as a radiation source: bodies, the visible cap, albedo and infrared models
(METHOD.md "Planet radiation")."""
