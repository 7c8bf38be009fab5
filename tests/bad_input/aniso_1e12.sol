MeshVersionFormatted 2
Dimension 2
SolAtVertices
4
1 3
1e12 0 1
1e12 0 1
1e12 0 1
1e12 0 1
End
