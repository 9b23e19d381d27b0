"""The rigid floating body: kinematics, radiation memory, hydrostatics and its Cummins equation
(physics.md section 5)."""
