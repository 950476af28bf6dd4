MODULE WALL
  !***********************************************************
  ! Two-layer wall, 60 mm, written as RobotStudio writes it
  !***********************************************************
  PERS tooldata tWeldGun:=[TRUE,[[0,0,400],[1,0,0,0]],[5,[0,0,100],[1,0,0,0],0,0,0]];
  TASK PERS wobjdata wobjTable:=[FALSE,TRUE,"",[[0,0,450],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];
  PERS seamdata seam1:=[0.5,0.5,[5,0,24,120,0,0,0,0,0],0.5,1,10,0,5,[5,0,24,120,0,0,0,0,0],0,1,[5,0,24,120,0,0,0,0,0],0,0,[0,0,0,0,0,0,0,0,0],0];
  PERS welddata weld1:=[6.667,0,[5,0,24,120,0,0,0,0,0],[0,0,0,0,0,0,0,0,0]];
  PERS weavedata weave1:=[1,0,3,4,0,0,0,0,0,0,0,0,0,0,0];
  CONST robtarget pHome:=[[1000,0,180],[0,1,0,0],[0,0,-1,0],[0,0,9E+09,9E+09,9E+09,9E+09]];
  CONST robtarget pStart1:=[[1000,0,151.5],[0,1,0,0],[0,0,-1,0],[0,0,9E+09,9E+09,9E+09,9E+09]];
  CONST robtarget pMid1:=[[1030,0,151.5],[0,1,0,0],[0,0,-1,0],[0,0,9E+09,9E+09,9E+09,9E+09]];
  CONST robtarget pEnd1:=[[1060,0,151.5],[0,1,0,0],[0,0,-1,0],[0,0,9E+09,9E+09,9E+09,9E+09]];
  CONST robtarget pStart2:=[[1060,0,153],[0,1,0,0],[0,0,-1,0],[0,0,9E+09,9E+09,9E+09,9E+09]];
  CONST robtarget pCir2:=[[1045,5,153],[0,1,0,0],[0,0,-1,0],[0,0,9E+09,9E+09,9E+09,9E+09]];
  CONST robtarget pMid2:=[[1030,0,153],[0,1,0,0],[0,0,-1,0],[0,0,9E+09,9E+09,9E+09,9E+09]];
  CONST robtarget pEnd2:=[[1000,0,153],[0,1,0,0],[0,0,-1,0],[0,0,9E+09,9E+09,9E+09,9E+09]];
  CONST jointtarget jPark:=[[0,10,0,0,-80,0],[0,0,9E+09,9E+09,9E+09,9E+09]];

  PROC main()
    ConfL\Off;
    TorchClean;
    MoveJ pHome,v100,fine,tWeldGun\WObj:=wobjTable;
    ArcLStart pStart1,v100,seam1,weld1,fine,tWeldGun\WObj:=wobjTable;
    ArcL pMid1,v100,seam1,weld1\Weave:=weave1,z1,tWeldGun\WObj:=wobjTable;
    ArcLEnd pEnd1,v100,seam1,weld1,fine,tWeldGun\WObj:=wobjTable;
    MoveL pStart2,v100,fine,tWeldGun\WObj:=wobjTable;
    SetDO doArcOn,1;
    MoveC pCir2,pMid2,v6.667,z1,tWeldGun\WObj:=wobjTable;
    MoveL pEnd2,vWeld,fine,tWeldGun\WObj:=wobjTable;
    SetDO doArcOn,0;
    MoveL Offs(pEnd2,0,0,40),v100,fine,tWeldGun\WObj:=wobjTable;
    WaitTime 1;
    MoveAbsJ jPark,v200,fine,tWeldGun;
  ENDPROC

  PROC TorchClean()
    ! cleaning station, not part of the build
    WaitTime 0.5;
  ENDPROC
ENDMODULE
