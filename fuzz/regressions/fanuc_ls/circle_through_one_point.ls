/PROG X
/MN
   1:C  P[1]  
    :   P[1] 10mm/sec FINE ;
/POS
P[1]{
   GP1:
	UF : 1, UT : 1,
	X = 1 mm, Y = 0 mm, Z = 0 mm,
	W = 0 deg, P = 0 deg, R = 0 deg
};
/END
