; Bar on a plate: five layers of one 120 mm pass, welded back and forth, 60 s dwell between layers.
; Written for the tests in the form WAAM gantry controllers take: feeds in mm/s (program.gcode.feed_unit: mm_per_s),
; M3 / M5 switching the torch, G4 dwells in both the P (ms) and S (s) forms, N numbers and a checksum.
%
N1 G21 G90 G17 G94 ; mm, absolute, XY plane
N2 G0 X-60 Y0 Z20
(layer 1)
N3 G0 Z2.0
N4 M3 S180 ; arc on, S the power set-point: not a path fact
N5 G1 X60 F8
N6 M5
N7 G0 Z12
N8 G4 S60 ; interlayer dwell
(layer 2)
N9 G0 X60 Y0 Z3.8
N10 M3
N11 G1 X-60
N12 M5
N13 G0 Z14
N14 G4 P60000 *85
(layer 3)
N15 G0 X-60 Y0 Z5.6
N16 M3
N17 G1 X60 F8
N18 M5
N19 G0 Z16
N20 G4 S60
(layer 4)
N21 G0 X60 Y0 Z7.4
N22 M3
N23 G1 X-60
N24 M5
N25 G0 Z18
N26 G4 S60
(layer 5)
N27 G0 X-60 Y0 Z9.2
N28 M3
N29 G1 X60 F8
N30 M5
N31 G0 Z40
N32 M30
%
