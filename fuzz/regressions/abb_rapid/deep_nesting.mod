MODULE M
CONST robtarget p:=[[[[[[[[[[[[1]]]]]]]]]]]];
PROC main()
MoveL p,v10,fine,tool0;
ENDPROC
ENDMODULE
