module superjoin_output_nodes_csv
  !! nodes.csv next to the CSV results: the coordinates of every node, so that
  !! displacements.csv and the other tables can be plotted without the deck.
  use superjoin_error, only: error_t, fatal_error, EXIT_IO
  use superjoin_kinds, only: ip
  use superjoin_model_types, only: model_t
  use superjoin_utils_text_buffer, only: text_buffer_t
  use superjoin_utils_process, only: temp_register, temp_unregister
  use superjoin_utils_strings, only: itoa, full_real
  implicit none (type, external)
  private

  character(*), parameter, public :: NODES_CSV = 'nodes.csv'

  public :: write_nodes_csv

contains

  subroutine write_nodes_csv(dir, model, error)
    !! DIR/nodes.csv (DIR exists): substructure,node,x,y,z with 17 digits, every
    !! node in the order of the deck; written to a temporary name and renamed.
    character(*), intent(in) :: dir
    type(model_t), intent(in) :: model
    type(error_t), allocatable, intent(out) :: error
    type(text_buffer_t), allocatable :: tb
    character(:), allocatable :: path, tmp
    integer :: isub
    integer(ip) :: n
    path = dir//'/'//NODES_CSV
    tmp = path//'.tmp'
    call temp_register(tmp)
    allocate (tb)
    call tb%open(tmp, error)
    if (allocated(error)) then
       call temp_unregister()
       return
    end if
    call tb%line('substructure,node,x,y,z')
    do isub = 1, size(model%subs)
       do n = 1, model%subs(isub)%nnode
          call tb%line(model%subs(isub)%name//','//itoa(int(model%subs(isub)%node_id(n)))//','// &
               full_real(model%subs(isub)%x(1, n))//','//full_real(model%subs(isub)%x(2, n))//','// &
               full_real(model%subs(isub)%x(3, n)))
       end do
    end do
    call tb%commit(tmp, path, '', error)
  end subroutine write_nodes_csv
end module superjoin_output_nodes_csv
