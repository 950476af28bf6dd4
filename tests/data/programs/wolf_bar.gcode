; A bar of three layers of two 60 mm tracks, 4 mm apart, written for the tests in ORNL's "Wolf" syntax (as in the
; SRP AM Prediction Challenge's calibration G-code, docs/THERMAL.md "A real G-code: SRP-4"): bare text lines,
; packed words without spaces (M5T2D1F0), M101 / M103 switching the pump (the arc), M6, F in mm/s, G4 S dwells.
; Layer Height: 0.08in
BEGINNING LAYER ; new layer starting
T1 ; TOOL CHANGE
M5T2D1F0; 
G1 Z30.0000 F5.0000 ; TRAVEL-Lift Tip For Travel
G1 X-2.0000 Y-30.0000 ; TRAVEL
G1 Z0.0000 ; TRAVEL-restore layer Z
; TYPE:INFILL
M101 ; Turn Pump on
G1 X-2.0000 Y30.0000 ; VOLUME-INFILL
G1 X2.0000 Y30.0000 ; VOLUME-INFILL
G1 X2.0000 Y-30.0000 ; VOLUME-INFILL
M6; 
M103 ; Turn Pump OFF; 
G4 S30 ;
BEGINNING LAYER ; new layer starting
M5T2D1F0T2D1F0; 
G1 Z32.0000 ; TRAVEL-Lift Tip For Travel
G1 X2.0000 Y-30.0000 ; TRAVEL
G1 Z2.0000 ; TRAVEL-restore layer Z
M101 ; Turn Pump on
G1 X2.0000 Y30.0000 F5.0000 ; VOLUME-INFILL
G1 X-2.0000 Y30.0000 ; VOLUME-INFILL
G1 X-2.0000 Y-30.0000 ; VOLUME-INFILL
M6; 
M103 ; Turn Pump OFF; 
G4 S20 ;
BEGINNING LAYER ; new layer starting
M5T2D1F0; 
G1 Z34.0000 ; TRAVEL-Lift Tip For Travel
G1 X-2.0000 Y-30.0000 ; TRAVEL
G1 Z4.0000 ; TRAVEL-restore layer Z
M101 ; Turn Pump on
G1 X-2.0000 Y30.0000 F5.0000 ; VOLUME-INFILL
G1 X2.0000 Y30.0000 ; VOLUME-INFILL
G1 X2.0000 Y-30.0000 ; VOLUME-INFILL
M6; 
M103 ; Turn Pump OFF; 
G1 F5.0000 Z60.0000 ; TRAVEL-Final Lift; 
