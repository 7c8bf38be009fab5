MeshVersionFormatted 2
Dimension 2
SolAtVertices
4
1 1
0.1
0.2
0.1
0.05
End
