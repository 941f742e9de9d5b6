"""Independent references for the solver: closed forms, the validation cases and their runner."""
