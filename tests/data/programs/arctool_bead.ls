/PROG  ARCTOOL_BEAD
/ATTR
OWNER		= MNEDITOR;
COMMENT		= "bead, weld schedule";
PROG_SIZE	= 1210;
CREATE		= DATE 25-02-03  TIME 14:05:10;
MODIFIED	= DATE 25-02-03  TIME 14:20:44;
FILE_NAME	= ;
VERSION		= 0;
LINE_COUNT	= 14;
MEMORY_SIZE	= 1650;
PROTECT		= READ_WRITE;
TCD:  STACK_SIZE	= 0,
      TASK_PRIORITY	= 50,
      TIME_SLICE	= 0,
      BUSY_LAMP_OFF	= 0,
      ABORT_REQUEST	= 0,
      PAUSE_REQUEST	= 0;
DEFAULT_GROUP	= 1,1,*,*,*;
CONTROL_CODE	= 00000000 00000000;
/APPL
  ARC Welding Equipment : 1,*,*,*,*;
/MN
   1:  UFRAME_NUM=6 ;
   2:  UTOOL_NUM=5 ;
   3:J P[1] 50% FINE ;
   4:L P[2] 200mm/sec FINE ;
   5:  Arc Start[3] ;
   6:  Weave Sine[1] ;
   7:L P[3] WELD_SPEED CNT100 ;
   8:  Weave End[1] ;
   9:L P[4] WELD_SPEED FINE Arc End[3] ;
  10:  WAIT 45.00(sec) ;
  11:  //L P[5] 100mm/sec FINE ;
L P[5] 100mm/sec
    FINE ;
! unnumbered statements from the offline editor ;
L P[6] 
    WELD_SPEED FINE Arc Start[3] ;
C P[7] P[8] 12mm/sec CNT100 ;
L P[9] WELD_SPEED FINE Arc End[3] ;
  12:  WAIT 1.50(sec) ;
  13:J P[10] R[4]% FINE ;
  14:  END ;
/POS
P[1]{
   GP1:
	UF : 6, UT : 5,		CONFIG : 'N U T, 0, 0, 0',
	X =    20.000  mm,	Y =     0.000  mm,	Z =    80.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[2:"approach"]{
   GP1:
	UF : 6, UT : 5,		CONFIG : 'N U T, 0, 0, 0',
	X =    20.000  mm,	Y =     0.000  mm,	Z =    10.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[3]{
   GP1:
	UF : 6, UT : 5,		CONFIG : 'N U T, 0, 0, 0',
	X =    60.000  mm,	Y =     0.000  mm,	Z =    10.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[4]{
   GP1:
	UF : 6, UT : 5,		CONFIG : 'N U T, 0, 0, 0',
	X =   100.000  mm,	Y =     0.000  mm,	Z =    10.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[5]{
   GP1:
	UF : 6, UT : 5,		CONFIG : 'N U T, 0, 0, 0',
	X =   100.000  mm,	Y =     0.000  mm,	Z =    11.500  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[6]{
   GP1:
	UF : 6, UT : 5,		CONFIG : 'N U T, 0, 0, 0',
	X =   100.000  mm,	Y =     0.000  mm,	Z =    11.500  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[7]{
   GP1:
	UF : 6, UT : 5,		CONFIG : 'N U T, 0, 0, 0',
	X =    80.000  mm,	Y =    20.000  mm,	Z =    11.500  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[8]{
   GP1:
	UF : 6, UT : 5,		CONFIG : 'N U T, 0, 0, 0',
	X =    60.000  mm,	Y =     0.000  mm,	Z =    11.500  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[9]{
   GP1:
	UF : 6, UT : 5,		CONFIG : 'N U T, 0, 0, 0',
	X =    20.000  mm,	Y =     0.000  mm,	Z =    11.500  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[10]{
   GP1:
	UF : 6, UT : 5,
	J1=     0.000 deg,	J2=     0.000 deg,	J3=     0.000 deg,
	J4=     0.000 deg,	J5=   -90.000 deg,	J6=     0.000 deg
};
/END
