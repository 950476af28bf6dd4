/PROG  WALL
/ATTR
OWNER		= MNEDITOR;
COMMENT		= "two-layer wall";
PROG_SIZE	= 1840;
CREATE		= DATE 24-03-11  TIME 09:12:40;
MODIFIED	= DATE 24-03-11  TIME 09:30:02;
FILE_NAME	= ;
VERSION		= 0;
LINE_COUNT	= 21;
MEMORY_SIZE	= 2280;
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
   1:  !Two-layer wall, 60 mm ;
   2:  UFRAME_NUM=1 ;
   3:  UTOOL_NUM=1 ;
   4:  CALL TORCH_CLEAN ;
   5:J  P[1] 30% FINE    ;
   6:L  P[2] 100mm/sec FINE Arc Start[1]   ;
   7:  Weave Sine[1] ;
   8:L  P[3] 40cm/min CNT100 COORD   ;
   9:  Weave End ;
  10:L  P[4] 40cm/min FINE    ;
  11:  Arc End[1] ;
  12:L  P[5] 100mm/sec FINE    ;
  13:  LBL[10] ;
  14:  Arc Start[2] ;
  15:C  P[6]  
    :   P[7] R[5]mm/sec CNT100 COORD   ;
  16:L  P[8] 40cm/min FINE Arc End[2]   ;
  17:L  P[9] 100mm/sec FINE Offset,PR[3]   ;
  18:  IF R[1]=1,JMP LBL[10] ;
  19:J  P[10] 30% FINE    ;
  20:  ! done ;
  21:  END ;
/POS
P[1]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 0',
	X =  1000.000  mm,	Y =     0.000  mm,	Z =   180.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
   GP2:
	UF : 1, UT : 1,
	J1=     0.000 deg,	J2=     0.000 deg
};
P[2:"start L1"]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 0',
	X =  1000.000  mm,	Y =     0.000  mm,	Z =   151.500  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
   GP2:
	UF : 1, UT : 1,
	J1=     0.000 deg,	J2=     0.000 deg
};
P[3]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 0',
	X =  1030.000  mm,	Y =     0.000  mm,	Z =   151.500  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
   GP2:
	UF : 1, UT : 1,
	J1=     0.000 deg,	J2=     0.000 deg
};
P[4]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 0',
	X =  1060.000  mm,	Y =     0.000  mm,	Z =   151.500  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
   GP2:
	UF : 1, UT : 1,
	J1=     0.000 deg,	J2=     0.000 deg
};
P[5]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 0',
	X =  1060.000  mm,	Y =     0.000  mm,	Z =   153.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
   GP2:
	UF : 1, UT : 1,
	J1=     0.000 deg,	J2=     0.000 deg
};
P[6]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 0',
	X =  1045.000  mm,	Y =     5.000  mm,	Z =   153.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
   GP2:
	UF : 1, UT : 1,
	J1=     0.000 deg,	J2=     0.000 deg
};
P[7]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 0',
	X =  1030.000  mm,	Y =     0.000  mm,	Z =   153.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
   GP2:
	UF : 1, UT : 1,
	J1=     0.000 deg,	J2=     0.000 deg
};
P[8]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 0',
	X =  1000.000  mm,	Y =     0.000  mm,	Z =   153.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
   GP2:
	UF : 1, UT : 1,
	J1=     0.000 deg,	J2=     0.000 deg
};
P[9]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 0',
	X =  1000.000  mm,	Y =     0.000  mm,	Z =   190.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
   GP2:
	UF : 1, UT : 1,
	J1=     0.000 deg,	J2=     0.000 deg
};
P[10]{
   GP1:
	UF : 1, UT : 1,
	J1=     0.000 deg,	J2=    10.000 deg,	J3=     0.000 deg,
	J4=     0.000 deg,	J5=   -80.000 deg,	J6=     0.000 deg
   GP2:
	UF : 1, UT : 1,
	J1=     0.000 deg,	J2=     0.000 deg
};
/END
