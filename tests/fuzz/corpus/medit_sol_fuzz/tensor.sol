MeshVersionFormatted 2
Dimension 2
SolAtVertices
2
1 3
100 0 1
4 1 9
End
