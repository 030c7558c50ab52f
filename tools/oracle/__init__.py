"""The independent checks: csgrt's output against a reading of the model
that shares none of its code (see tools/oracle/oracle/)."""
