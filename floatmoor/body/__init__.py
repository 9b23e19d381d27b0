"""The rigid floating body: kinematics, radiation memory, hydrostatics and its Cummins equation
(docs/theory/floater.md)."""
